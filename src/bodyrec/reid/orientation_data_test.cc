// Orientation on real Kinect v2 skeletons (NTU RGB+D samples, ../shared/datasets/ntu_skeleton).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <map>

#include <gtest/gtest.h>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "test_support.h"

namespace bodyrec {
namespace {

struct OrientRun {
  int frames = 0;
  std::map<uint64_t, std::vector<ViewEstimate>> per_body;
};

OrientRun orient_file(const std::string& file, ViewMethod method) {
  const NtuSkeleton s = read_ntu_skeleton(file);
  RecordingMeta meta;
  double rms[2];
  fit_ntu_cameras(s, meta, rms);
  OrientationOptions o;
  o.method = method;
  o.use_faces = false;  // no colour in the skeleton files
  OrientationEstimator est(meta, o);
  OrientRun r;
  const auto bodies = ntu_bodies(s, file);
  for (size_t i = 0; i < bodies.size(); ++i) {
    RgbdFrame f;
    f.index = static_cast<int>(i);
    f.time_s = static_cast<double>(i) / 30;
    f.bodies = bodies[i];
    for (const Body& b : f.bodies) r.per_body[b.tracking_id].push_back(est.estimate(f, BodyRef::of(b, cv::Mat())));
    ++r.frames;
  }
  return r;
}

// A056 "giving something to other person", camera 3: the first performer faces the camera (median
// shoulder-and-hip yaw 9 degrees, the thesis yaw of its SpineBase quaternion 15), the second is turned
// away from it towards the first (FL/SL).
TEST(OrientationNtu, GivingSomethingFirstPersonFacesTheCamera) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S017C003P020R002A056.skeleton");
  const OrientRun r = orient_file(file.string(), ViewMethod::kRobust);
  EXPECT_EQ(r.frames, 80);
  ASSERT_EQ(r.per_body.size(), 2u);
  const auto& first = r.per_body.begin()->second;  // the smaller Kinect id is the first performer
  EXPECT_EQ(first.size(), 80u);
  int front = 0, front_left = 0, jumps = 0;
  for (size_t i = 0; i < first.size(); ++i) {
    ASSERT_TRUE(first[i].view) << first[i].reason;
    front += *first[i].view == View::F;
    front_left += *first[i].view == View::FL;
    if (i > 0) jumps += angle_diff_deg(first[i].yaw_deg, first[i - 1].yaw_deg) > 15;
  }
  EXPECT_GE(front, 40) << "of 80 frames";  // measured 47
  EXPECT_EQ(front + front_left, 80);       // never a side or back view
  EXPECT_LE(jumps, 1);  // continuity: frame-to-frame jumps above 15 degrees (measured 1)
  const auto& second = std::next(r.per_body.begin())->second;
  int side_or_front_left = 0;
  for (const auto& v : second) side_or_front_left += v.view == View::FL || v.view == View::SL;
  EXPECT_EQ(side_or_front_left, 80);
}

// A001 "drink water" from camera 1, which sees the performers at 45 degrees (NTU's setup): FL throughout.
TEST(OrientationNtu, Camera1SeesTheFortyFiveDegreeView) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S001C001P001R001A001.skeleton");
  const OrientRun r = orient_file(file.string(), ViewMethod::kRobust);
  EXPECT_EQ(r.frames, 103);
  ASSERT_EQ(r.per_body.size(), 1u);
  int fl = 0;
  for (const auto& v : r.per_body.begin()->second) fl += v.view == View::FL;
  EXPECT_GE(fl, 95);  // measured 103
}

// Every sample: every body gets a view in every frame from its skeleton, yaws change smoothly, and the
// thesis rule, without a face flag, names the reason when it cannot decide.
TEST(OrientationNtu, AllSamplesContinuousAndThesisSaysWhy) {
  BODYREC_REQUIRE_DATA(dir, "ntu_skeleton/samples");
  int files = 0, bodies = 0, big = 0, thesis_none = 0, thesis_face_reason = 0, thesis_views = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".skeleton") continue;
    ++files;
    const OrientRun robust = orient_file(entry.path().string(), ViewMethod::kRobust);
    for (const auto& [id, views] : robust.per_body)
      for (size_t i = 0; i < views.size(); ++i) {
        ++bodies;
        ASSERT_TRUE(views[i].view) << entry.path() << " frame " << i << ": " << views[i].reason;
        if (i > 0) big += angle_diff_deg(views[i].yaw_deg, views[i - 1].yaw_deg) > 30;
      }
    const OrientRun thesis = orient_file(entry.path().string(), ViewMethod::kThesis);
    for (const auto& [id, views] : thesis.per_body)
      for (const auto& v : views) {
        if (v.view) {
          ++thesis_views;
          continue;
        }
        ++thesis_none;
        EXPECT_FALSE(v.reason.empty());
        thesis_face_reason += v.reason.find("face flag") != std::string::npos;
      }
  }
  EXPECT_EQ(files, 12);
  EXPECT_EQ(bodies, 1426);
  // Frame-to-frame yaw jumps above 30 degrees: the skeleton itself jumps when two people hug (A055).
  std::printf("yaw jumps above 30 degrees: %d of %d body-frames\n", big, bodies);
  EXPECT_LE(big, bodies / 100);
  EXPECT_EQ(thesis_views + thesis_none, bodies);
  EXPECT_GT(thesis_face_reason, 0);
}

}  // namespace
}  // namespace bodyrec
