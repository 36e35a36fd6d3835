#include <gtest/gtest.h>

#include "bodyrec/rgbd/green_screen.h"
#include "bodyrec/rgbd/synth.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(BackgroundRemoval, CopiesTheColourAtTheMappedPositionIntoTheBodysImage) {
  RecordingMeta m;
  m.depth = kinect2_depth_intrinsics();
  m.color = scaled(kinect2_color_intrinsics(), 960, 540);
  m.depth_to_color = kinect2_depth_to_color();
  // Colour pixels encode their own position: B = u % 256, G = v % 256, R = u / 256 * 16 + v / 256.
  cv::Mat color(540, 960, CV_8UC3);
  for (int v = 0; v < 540; ++v)
    for (int u = 0; u < 960; ++u) color.at<cv::Vec3b>(v, u) = cv::Vec3b(u % 256, v % 256, (u / 256) * 16 + v / 256);
  cv::Mat depth(424, 512, CV_16U, cv::Scalar(2500));
  cv::Mat body(424, 512, CV_8U, cv::Scalar(kNoBody));
  body(cv::Rect(100, 50, 40, 60)).setTo(2);
  body(cv::Rect(300, 200, 10, 10)).setTo(5);
  depth.at<uint16_t>(60, 110) = 0;  // a body pixel without depth stays transparent
  BackgroundRemoval removal(m);
  std::array<cv::Mat, kMaxBodies> out;
  removal.apply(depth, body, color, out);
  for (int s : {0, 1, 3, 4}) EXPECT_TRUE(out[static_cast<size_t>(s)].empty());
  ASSERT_EQ(out[2].size(), cv::Size(512, 424));
  ASSERT_EQ(out[2].type(), CV_8UC4);
  EXPECT_EQ(cv::countNonZero(cv::Mat(out[2].reshape(1, 424 * 512).col(3))), 40 * 60 - 1);
  EXPECT_EQ(cv::countNonZero(cv::Mat(out[5].reshape(1, 424 * 512).col(3))), 100);
  for (const cv::Point p : {cv::Point(100, 50), cv::Point(139, 109), cv::Point(305, 205)}) {
    const auto c = project(m.color, m.depth_to_color.apply(unproject(m.depth, p.x, p.y, 2.5)));
    const cv::Vec4b got = out[body.at<uint8_t>(p)].at<cv::Vec4b>(p);
    const int cu = static_cast<int>(std::lround(c->x)), cv_ = static_cast<int>(std::lround(c->y));
    EXPECT_EQ(got, cv::Vec4b(cu % 256, cv_ % 256, (cu / 256) * 16 + cv_ / 256, 255)) << p;
  }
  EXPECT_EQ(out[2].at<cv::Vec4b>(60, 110), cv::Vec4b(0, 0, 0, 0));
  EXPECT_EQ(out[2].at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));
  EXPECT_THROW(removal.apply(depth, body, cv::Mat(100, 100, CV_8UC3), out), InputError);
}

TEST(BackgroundRemoval, SynthPeopleMapOntoThemselvesNotOntoTheRoom) {
  SynthOptions o;
  o.people = 2;
  o.frames = 60;
  o.seed = 3;
  Synthesizer synth(o);
  const RgbdFrame room = synth.render(0);  // nobody in view yet
  ASSERT_TRUE(room.bodies.empty());
  const RgbdFrame f = synth.render(30);
  BackgroundRemoval removal(synth.meta());
  std::array<cv::Mat, kMaxBodies> out;
  removal.apply(f.depth, f.body_index, f.color, out);
  // Most cut-out pixels show a person, i.e. differ from the empty room's colour at the same place (not
  // all: light skin under this light is close to the wall's colour, and edges see parallax).
  cv::Mat coords;
  map_depth_to_color(f.depth, 0.001, synth.meta().depth, synth.meta().color, synth.meta().depth_to_color, coords);
  for (int s = 0; s < 2; ++s) {
    ASSERT_FALSE(out[static_cast<size_t>(s)].empty());
    int body = 0, person = 0;
    for (int v = 0; v < 424; ++v)
      for (int u = 0; u < 512; ++u) {
        const cv::Vec4b c = out[static_cast<size_t>(s)].at<cv::Vec4b>(v, u);
        if (c[3] == 0) continue;
        ++body;
        const cv::Vec2f p = coords.at<cv::Vec2f>(v, u);
        const cv::Vec3b bg = room.color.at<cv::Vec3b>(cvRound(p[1]), cvRound(p[0]));
        if (std::abs(c[0] - bg[0]) + std::abs(c[1] - bg[1]) + std::abs(c[2] - bg[2]) > 30) ++person;
      }
    EXPECT_GT(body, 2000);
    EXPECT_GT(person, 0.9 * body) << "slot " << s;
  }
}

}  // namespace
}  // namespace bodyrec
