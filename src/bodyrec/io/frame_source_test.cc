#include "bodyrec/io/frame_source.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/sinks.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::TempDir;

// Writes n solid images named img0.png.. whose blue channel holds their index.
void write_images(const TempDir& dir, int n) {
  for (int i = 0; i < n; ++i)
    cv::imwrite((dir / ("img" + std::to_string(i) + ".png")).string(), cv::Mat(8, 12, CV_8UC3, cv::Scalar(i, 0, 0)));
}

std::vector<int> indices(FrameSource& source) {
  std::vector<int> out;
  Frame f;
  while (source.read(f)) out.push_back(f.index);
  return out;
}

TEST(FrameSource, DirectorySortedWithSelection) {
  TempDir dir;
  write_images(dir, 5);
  SourceOptions o;
  o.path = dir.path().string();
  auto all = open_source(o);
  EXPECT_EQ(all->frame_count().value(), 5);
  Frame f;
  ASSERT_TRUE(all->read(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 0);
  EXPECT_EQ(f.image.size(), cv::Size(12, 8));
  o.start = 1;
  o.every = 2;
  auto some = open_source(o);
  EXPECT_EQ(some->frame_count().value(), 2);
  EXPECT_EQ(indices(*some), (std::vector<int>{1, 3}));
  o.max_frames = 1;
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{1}));
}

TEST(FrameSource, SingleImageAndGlob) {
  TempDir dir;
  write_images(dir, 3);
  SourceOptions o;
  o.path = (dir / "img2.png").string();
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0}));
  o.path = (dir / "img*.png").string();
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0, 1, 2}));
  o.path = (dir / "nothing*.png").string();
  EXPECT_THROW(open_source(o), InputError);
}

TEST(FrameSource, VideoFramesAndTimestamps) {
  TempDir dir;
  const std::string path = (dir / "v.avi").string();
  {
    cv::VideoWriter w(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48));
    ASSERT_TRUE(w.isOpened());
    for (int i = 0; i < 6; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(40 * i, 0, 0)));
  }
  SourceOptions o;
  o.path = path;
  o.start = 2;
  auto source = open_source(o);
  EXPECT_EQ(source->frame_count().value(), 4);
  Frame f;
  ASSERT_TRUE(source->read(f));
  EXPECT_EQ(f.index, 2);
  EXPECT_DOUBLE_EQ(f.time_s, 0.2);
  EXPECT_EQ(indices(*source), (std::vector<int>{3, 4, 5}));
}

TEST(FrameSource, BadInputsAreInputErrorsNamingThePath) {
  TempDir dir;
  auto message = [](const SourceOptions& o) {
    try {
      open_source(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SourceOptions o;
  o.path = (dir / "missing.avi").string();
  EXPECT_NE(message(o).find("missing.avi"), std::string::npos);
  o.path = dir.path().string();  // empty directory
  EXPECT_NE(message(o).find("no images in directory " + dir.path().string()), std::string::npos);
  testing::write_text(dir / "text.avi", "this is not a video\n");
  o.path = (dir / "text.avi").string();
  EXPECT_NE(message(o).find("text.avi"), std::string::npos);
  testing::write_text(dir / "empty.avi", "");
  o.path = (dir / "empty.avi").string();
  EXPECT_NE(message(o).find("empty"), std::string::npos);
}

TEST(FrameSource, CorruptImageInDirectoryNamesTheFile) {
  TempDir dir;
  write_images(dir, 2);
  testing::write_text(dir / "img9.png", "not a png");
  SourceOptions o;
  o.path = dir.path().string();
  auto source = open_source(o);
  Frame f;
  EXPECT_TRUE(source->read(f));
  EXPECT_TRUE(source->read(f));
  try {
    source->read(f);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("img9.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frame 2"), std::string::npos) << e.what();
  }
}

TEST(SourceOptions, CheckRejectsBadValues) {
  SourceOptions o;
  EXPECT_THROW(o.check(), UsageError);  // no input at all
  o.path = "x.avi";
  o.every = 0;
  EXPECT_THROW(o.check(), UsageError);
  o.every = 1;
  o.start = -1;
  EXPECT_THROW(o.check(), UsageError);
  o.start = 0;
  o.camera = 0;
  EXPECT_THROW(o.check(), UsageError);
  o.camera = -1;
  EXPECT_NO_THROW(o.check());
}

TEST(Sinks, MotRowsAreOneBasedWithTwoDecimalBoxes) {
  TempDir dir;
  const auto path = dir / "out.mot";
  {
    MotWriter w(path.string());
    w.write(0, -1, Box(1.234, 2, 3.5, 4), 0.5);
    w.write(9, 7, Box(10, 20, 30, 40), -1.25);
    w.end_frame();
  }
  EXPECT_EQ(testing::read_text(path),
            "1,-1,1.23,2.00,3.50,4.00,0.500000,-1,-1,-1\n10,7,10.00,20.00,30.00,40.00,-1.250000,-1,-1,-1\n");
}

TEST(Sinks, JsonlOneObjectPerLine) {
  TempDir dir;
  const auto path = dir / "sub" / "out.jsonl";
  {
    JsonlWriter w(path.string());
    w.write({{"frame", 0}});
    w.write({{"frame", 1}, {"detections", nlohmann::json::array()}});
  }
  EXPECT_EQ(testing::read_text(path), "{\"frame\":0}\n{\"detections\":[],\"frame\":1}\n");
}

TEST(Sinks, AnnotatedFolderAndVideo) {
  TempDir dir;
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  {
    AnnotatedWriter pngs((dir / "frames").string(), 10);
    pngs.write(3, image);
    pngs.write(12, image);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "frames" / "000003.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "frames" / "000012.png"));
  const std::string video = (dir / "out.avi").string();
  {
    AnnotatedWriter w(video, 10);
    for (int i = 0; i < 4; ++i) w.write(i, image);
  }
  cv::VideoCapture back(video);
  ASSERT_TRUE(back.isOpened());
  EXPECT_EQ(static_cast<int>(back.get(cv::CAP_PROP_FRAME_COUNT)), 4);
  EXPECT_TRUE(is_video_path("a.MP4"));
  EXPECT_FALSE(is_video_path("frames/"));
}

}  // namespace
}  // namespace bodyrec
