#include "bodyrec/io/frame_source.h"

#include <algorithm>
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

TEST(FrameSource, ThreePngsSortedByNameWithStartEveryMaxFrames) {
  TempDir dir;
  // Written out of order, with a non-image file and a sub-folder that must be skipped.
  for (const char* name : {"c.png", "a.png", "b.png"})
    cv::imwrite((dir / name).string(), cv::Mat(6, 10, CV_8UC3, cv::Scalar(name[0], 0, 0)));
  testing::write_text(dir / "notes.txt", "not an image");
  std::filesystem::create_directories(dir / "sub.png");
  SourceOptions o;
  o.path = dir.path().string();
  auto source = open_source(o);
  EXPECT_EQ(source->frame_count().value(), 3);
  EXPECT_FALSE(source->fps().has_value());
  EXPECT_EQ(source->describe(), dir.path().string());
  Frame f;
  for (const char* name : {"a.png", "b.png", "c.png"}) {
    ASSERT_TRUE(source->read(f));
    EXPECT_EQ(f.name, (dir / name).string());
    EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], name[0]);
    EXPECT_EQ(f.image.type(), CV_8UC3);
  }
  EXPECT_FALSE(source->read(f));
  EXPECT_FALSE(source->read(f));  // stays at the end

  struct Case {
    int start, every, max_frames;
    std::vector<int> expected;
  };
  for (const Case& c : std::vector<Case>{{0, 1, -1, {0, 1, 2}},
                                         {1, 1, -1, {1, 2}},
                                         {0, 2, -1, {0, 2}},
                                         {0, 1, 2, {0, 1}},
                                         {2, 1, -1, {2}},
                                         {3, 1, -1, {}},
                                         {0, 5, -1, {0}},
                                         {0, 1, 0, {}},
                                         {1, 2, 1, {1}}}) {
    o.start = c.start;
    o.every = c.every;
    o.max_frames = c.max_frames;
    auto selected = open_source(o);
    EXPECT_EQ(selected->frame_count().value(), static_cast<int>(c.expected.size()))
        << "start " << c.start << " every " << c.every << " max " << c.max_frames;
    EXPECT_EQ(indices(*selected), c.expected) << "start " << c.start << " every " << c.every << " max "
                                              << c.max_frames;
  }
}

TEST(FrameSource, SingleImageAndGlobPattern) {
  TempDir dir;
  write_images(dir, 3);
  SourceOptions o;
  o.path = (dir / "img1.png").string();
  auto one = open_source(o);
  EXPECT_EQ(one->frame_count().value(), 1);
  Frame f;
  ASSERT_TRUE(one->read(f));
  EXPECT_EQ(f.index, 0);
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 1);
  EXPECT_FALSE(one->read(f));
  o.path = (dir / "img?.png").string();
  auto glob = open_source(o);
  EXPECT_EQ(glob->frame_count().value(), 3);
  ASSERT_TRUE(glob->read(f));
  EXPECT_EQ(f.name, (dir / "img0.png").string());
  // Brackets are not pattern characters: a folder named like this is read as a path.
  std::filesystem::create_directories(dir / "run[1]");
  cv::imwrite((dir / "run[1]" / "x.png").string(), cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0)));
  o.path = (dir / "run[1]").string();
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0}));
  o.path = (dir / "run[1]" / "x.png").string();
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0}));
  o.path = (dir / "*.png").string();
  o.every = 2;
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0, 2}));
}

TEST(FrameSource, MissingInputsAreInputErrorsNamingThePath) {
  TempDir dir;
  auto message = [](const SourceOptions& o) {
    try {
      open_source(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    } catch (const std::exception& e) {
      return std::string("wrong exception: ") + e.what();
    }
    return std::string("no error");
  };
  SourceOptions o;
  o.path = (dir / "missing.avi").string();
  EXPECT_THROW(open_source(o), InputError);
  EXPECT_EQ(message(o), "input not found: " + o.path);
  o.path = (dir / "missing.png").string();
  EXPECT_EQ(message(o), "input not found: " + o.path);
  o.path = (dir / "nothing*.png").string();
  EXPECT_EQ(message(o), "no images match the pattern " + o.path);
  o.path = (dir / "no-such-folder" / "*.png").string();  // the glob's folder does not exist
  EXPECT_EQ(message(o), "no images match the pattern " + o.path);
  std::filesystem::create_directories(dir / "empty");
  testing::write_text(dir / "empty" / "readme.txt", "no images here");
  o.path = (dir / "empty").string();
  EXPECT_THROW(open_source(o), InputError);
  EXPECT_EQ(message(o), "no images in directory " + o.path);
  testing::write_text(dir / "text.avi", "this is a text file renamed .avi\n");
  o.path = (dir / "text.avi").string();
  EXPECT_THROW(open_source(o), InputError);
  EXPECT_NE(message(o).find(o.path), std::string::npos) << message(o);
  testing::write_text(dir / "text.mp4", std::string(4096, 'x'));
  o.path = (dir / "text.mp4").string();
  EXPECT_NE(message(o).find(o.path), std::string::npos) << message(o);
}

TEST(FrameSource, CorruptSingleImageNamesTheFile) {
  TempDir dir;
  testing::write_text(dir / "broken.png", "\x89PNG but not really");
  SourceOptions o;
  o.path = (dir / "broken.png").string();
  auto source = open_source(o);
  Frame f;
  try {
    source->read(f);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), o.path + ": cannot decode image (frame 0)");
  }
}

TEST(FrameSource, CorruptPngAmongValidOnesFailsAtItsTurn) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
  testing::write_text(dir / "b.png", "plain text with a png name");
  cv::imwrite((dir / "c.png").string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
  SourceOptions o;
  o.path = dir.path().string();
  auto source = open_source(o);  // opening does not decode
  EXPECT_EQ(source->frame_count().value(), 3);
  Frame f;
  ASSERT_TRUE(source->read(f));
  EXPECT_EQ(f.index, 0);
  EXPECT_THROW(source->read(f), InputError);
  // Skipping the corrupt frame with --every avoids it.
  o.every = 2;
  EXPECT_EQ(indices(*open_source(o)), (std::vector<int>{0, 2}));
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

TEST(SourceOptions, CheckMessagesNameTheOption) {
  auto usage = [](const SourceOptions& o) {
    try {
      o.check();
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SourceOptions o;
  o.path = "v.avi";
  o.every = -3;
  EXPECT_EQ(usage(o), "SourceOptions.every must be >= 1 (got -3)");
  o.every = 1;
  o.start = -2;
  EXPECT_EQ(usage(o), "SourceOptions.start must be >= 0 (got -2)");
  o.start = 0;
  o.max_frames = -2;
  EXPECT_NE(usage(o).find("SourceOptions.max_frames"), std::string::npos);
  o.max_frames = 0;
  EXPECT_NO_THROW(o.check());
  o.camera = 1;
  EXPECT_NE(usage(o).find("not both"), std::string::npos);
  o.path.clear();
  EXPECT_NO_THROW(o.check());  // a camera alone is fine
  // open_source checks the options before touching the path.
  o.camera = -1;
  o.path = "/no/such/file.avi";
  o.every = 0;
  EXPECT_THROW(open_source(o), UsageError);
}

TEST(FrameSource, ImagePathsByExtension) {
  EXPECT_TRUE(is_image_path("a.png"));
  EXPECT_TRUE(is_image_path("dir/A.JPG"));
  EXPECT_TRUE(is_image_path("x.jpeg"));
  EXPECT_TRUE(is_image_path("x.TiF"));
  EXPECT_TRUE(is_image_path("x.webp"));
  EXPECT_FALSE(is_image_path("x.avi"));
  EXPECT_FALSE(is_image_path("png"));
  EXPECT_FALSE(is_image_path("x.png.txt"));
}

TEST(Sinks, JsonlOneLinePerObjectFlushedImmediately) {
  TempDir dir;
  const auto path = dir / "out.jsonl";
  JsonlWriter w(path.string());
  EXPECT_FALSE(w.to_stdout());
  for (int i = 0; i < 3; ++i) {
    w.write({{"frame", i}, {"detections", {{{"box", {1.5, 2, 3, 4}}, {"score", 0.25}}}}});
    // Each line is on disk before the writer is closed.
    const std::string so_far = testing::read_text(path);
    EXPECT_EQ(std::count(so_far.begin(), so_far.end(), '\n'), i + 1);
  }
  const std::string text = testing::read_text(path);
  EXPECT_EQ(text.substr(0, text.find('\n')), R"({"detections":[{"box":[1.5,2,3,4],"score":0.25}],"frame":0})");
  EXPECT_TRUE(JsonlWriter("").to_stdout());
  EXPECT_TRUE(JsonlWriter("-").to_stdout());
}

TEST(Sinks, UnwritableOutputsAreProcessingErrors) {
  TempDir dir;
  testing::write_text(dir / "file", "x");
  EXPECT_THROW(JsonlWriter((dir / "file" / "out.jsonl").string()), ProcessingError);
  EXPECT_THROW(MotWriter((dir / "file" / "out.txt").string()), ProcessingError);
  EXPECT_THROW(AnnotatedWriter((dir / "file" / "frames").string(), 10), ProcessingError);
  std::filesystem::create_directories(dir / "folder.jsonl");
  EXPECT_THROW(JsonlWriter((dir / "folder.jsonl").string()), ProcessingError);
}

TEST(Sinks, MotWriterRoundTripsThroughReadMot) {
  TempDir dir;
  const auto path = dir / "res.txt";
  {
    MotWriter w(path.string());
    w.write(0, -1, Box(10.126, 20, 30, 60), 0.75);
    w.end_frame();
    w.end_frame();  // a frame without detections writes nothing
    w.write(2, 3, Box(0.004, 1, 2, 3), 1.5);
    w.end_frame();
  }
  EXPECT_EQ(testing::read_text(path),
            "1,-1,10.13,20.00,30.00,60.00,0.750000,-1,-1,-1\n3,3,0.00,1.00,2.00,3.00,1.500000,-1,-1,-1\n");
}

TEST(Sinks, MotRowsAreOneBasedWithTwoDecimalBoxes) {
  TempDir dir;
  const auto path = dir / "out.mot";
  {
    MotWriter w(path.string());
    w.write(0, -1, Box(1.234, 2, 3.5, 4), 0.5);
    w.write(9, 7, Box(10, 20, 30, 40), -1.25);
    w.write(10, 7, Box(-0.003, -0.0049, 30, 40), 1);  // never "-0.00"
    w.end_frame();
  }
  EXPECT_EQ(testing::read_text(path),
            "1,-1,1.23,2.00,3.50,4.00,0.500000,-1,-1,-1\n10,7,10.00,20.00,30.00,40.00,-1.250000,-1,-1,-1\n"
            "11,7,0.00,0.00,30.00,40.00,1.000000,-1,-1,-1\n");
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
  cv::Mat first;
  ASSERT_TRUE(back.read(first));
  EXPECT_EQ(first.size(), cv::Size(64, 48));
  // Frames of other sizes (a folder of photos) are scaled into the video's size, not dropped.
  const std::string mixed = (dir / "mixed.avi").string();
  {
    AnnotatedWriter w(mixed, 10);
    w.write(0, image);
    w.write(1, cv::Mat(96, 32, CV_8UC3, cv::Scalar(255, 255, 255)));  // tall: 16 x 48 in the middle
    w.write(2, image);
  }
  cv::VideoCapture three(mixed);
  ASSERT_TRUE(three.isOpened());
  EXPECT_EQ(static_cast<int>(three.get(cv::CAP_PROP_FRAME_COUNT)), 3);
  cv::Mat f;
  ASSERT_TRUE(three.read(f) && three.read(f));
  ASSERT_EQ(f.size(), cv::Size(64, 48));
  EXPECT_GT(f.at<cv::Vec3b>(24, 32)[0], 200);  // the white image in the middle
  EXPECT_LT(f.at<cv::Vec3b>(24, 4)[0], 40);    // black beside it
  EXPECT_TRUE(is_video_path("a.MP4"));
  EXPECT_TRUE(is_video_path("a.mkv"));
  EXPECT_TRUE(is_video_path("a.mov"));
  EXPECT_FALSE(is_video_path("frames/"));
}

TEST(Sinks, AnnotatedVideoInEveryContainer) {
  TempDir dir;
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  for (const char* name : {"a.mp4", "b.MP4", "c.mkv", "d.mov", "e.AVI"}) {
    const std::string video = (dir / "videos" / name).string();  // the folder is created
    {
      AnnotatedWriter w(video, 25);
      EXPECT_EQ(w.path(), video);
      for (int i = 0; i < 3; ++i) w.write(i, image);
    }
    cv::VideoCapture back(video, cv::CAP_FFMPEG);
    ASSERT_TRUE(back.isOpened()) << name;
    cv::Mat frame;
    int frames = 0;
    while (back.read(frame)) {
      EXPECT_EQ(frame.size(), image.size()) << name;
      ++frames;
    }
    EXPECT_EQ(frames, 3) << name;
  }
}

}  // namespace
}  // namespace bodyrec
