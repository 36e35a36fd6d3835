// The command line as a user meets it: help, usage errors, input errors, and the outputs of `detect`.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

TEST(Cli, HelpListsSubcommandsAndExitCodes) {
  const RunResult r = run_bodyrec({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("detect"), std::string::npos);
  EXPECT_NE(r.out.find("eval"), std::string::npos);
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos);
  const RunResult sub = run_bodyrec({"detect", "--help"});
  EXPECT_EQ(sub.exit_code, 0);
  EXPECT_NE(sub.out.find("--win-stride"), std::string::npos);
  EXPECT_NE(sub.out.find("--every INT:POSITIVE=1"), std::string::npos);  // defaults are shown
}

TEST(Cli, UsageErrorsExitTwo) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  EXPECT_EQ(run_bodyrec({"nosuchcommand"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--every", "0"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--preset", "fast"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--scale", "0.9"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval", "detect", "--source", vtest_path().string()}).exit_code, 2);  // no --gt
}

TEST(Cli, InputErrorsExitThreeNamingThePath) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  expect_one_line_error(run_bodyrec({"detect", (dir / "missing.avi").string()}), 3, "missing.avi");
  write_text(dir / "notes.avi", "just some text, renamed\n");
  expect_one_line_error(run_bodyrec({"detect", (dir / "notes.avi").string()}), 3, (dir / "notes.avi").string());
  fs::create_directories(dir / "empty");
  expect_one_line_error(run_bodyrec({"detect", (dir / "empty").string()}), 3, (dir / "empty").string());
  expect_one_line_error(run_bodyrec({"detect", vtest_path().string(), "--model", (dir / "notes.avi").string()}), 3,
                        "notes.avi");
  expect_one_line_error(
      run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", (dir / "gt.xml").string()}), 3,
      "gt.xml");
}

TEST(Cli, DetectWritesJsonlMotAndAnnotatedFrames) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  const auto jsonl = dir / "d.jsonl", mot = dir / "d.mot", frames = dir / "frames";
  const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--max-frames", "3", "--jsonl", jsonl.string(),
                                   "--mot", mot.string(), "--annotate", frames.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(read_text(jsonl));
  ASSERT_EQ(rows.size(), 3u);
  int detections = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto row = nlohmann::json::parse(rows[i]);
    ASSERT_TRUE(row.is_object()) << rows[i];
    EXPECT_EQ(row.size(), 3u) << rows[i];
    for (const char* key : {"frame", "time", "detections"}) EXPECT_TRUE(row.contains(key)) << key;
    ASSERT_TRUE(row["detections"].is_array()) << rows[i];
    EXPECT_EQ(row["frame"].get<int>(), static_cast<int>(i));
    EXPECT_NEAR(row["time"].get<double>(), i / 10.0, 1e-9);  // vtest.avi is 10 fps
    for (const auto& d : row["detections"]) {
      ASSERT_EQ(d["box"].size(), 4u);
      for (const auto& v : d["box"]) EXPECT_TRUE(v.is_number()) << d;
      EXPECT_GT(d["box"][2].get<double>(), 0) << d;
      EXPECT_GT(d["box"][3].get<double>(), 0) << d;
      EXPECT_TRUE(d["score"].is_number());
      ++detections;
    }
  }
  EXPECT_GT(detections, 3);
  int mot_rows = 0;
  for (const auto& line : lines_of(read_text(mot))) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 9) << line;  // 10 fields
    EXPECT_EQ(line.substr(line.find(','), 4), ",-1,") << line;  // untracked: id -1
    EXPECT_EQ(line.substr(line.size() - 9), ",-1,-1,-1") << line;
    const int frame = std::stoi(line.substr(0, line.find(',')));
    EXPECT_GE(frame, 1);
    EXPECT_LE(frame, 3);
    ++mot_rows;
  }
  EXPECT_EQ(mot_rows, detections);
  for (const char* name : {"000000.png", "000001.png", "000002.png"}) {
    const cv::Mat png = cv::imread((frames / name).string());
    EXPECT_EQ(png.size(), cv::Size(768, 576)) << name;  // vtest.avi's frame size
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(frames), fs::directory_iterator()), 3);
  EXPECT_TRUE(r.err.empty()) << r.err;  // -q: nothing on stderr
}

TEST(Cli, ErrorMidRunKeepsEverythingBefore) {
  TempDir dir;
  const cv::Mat image(200, 150, CV_8UC3, cv::Scalar(120, 120, 120));
  cv::imwrite((dir / "a.png").string(), image);
  cv::imwrite((dir / "b.png").string(), image);
  write_text(dir / "c.png", "not an image");
  const auto jsonl = dir / "out.jsonl";
  const RunResult r = run_bodyrec({"detect", dir.path().string(), "--jsonl", jsonl.string(), "-q"});
  expect_one_line_error(r, 3, "c.png");
  const std::string text = read_text(jsonl);
  EXPECT_EQ(text.back(), '\n');  // complete lines only
  const auto rows = lines_of(text);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(rows[0])["frame"].get<int>(), 0);
  EXPECT_EQ(nlohmann::json::parse(rows[1])["frame"].get<int>(), 1);
  EXPECT_NE(r.err.find((dir / "c.png").string()), std::string::npos) << r.err;
}

TEST(Cli, JsonlGoesToStdoutByDefault) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(200, 150, CV_8UC3, cv::Scalar(0, 0, 0)));
  const RunResult r = run_bodyrec({"detect", (dir / "a.png").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["detections"].size(), 0u);
}

TEST(Cli, MoreUsageErrorsExitTwoWithOneLine) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(0)));
  const std::string image = (dir / "a.png").string();
  RunResult r = run_bodyrec({"detect", image, "--every", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--every"), std::string::npos) << r.err;
  r = run_bodyrec({"detect", image, "--start", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--start"), std::string::npos) << r.err;
  r = run_bodyrec({"detect", image, "--max-frames", "-5"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--max-frames"), std::string::npos) << r.err;
  r = run_bodyrec({"detect", image, "--camera", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("not both"), std::string::npos) << r.err;
  r = run_bodyrec({"detect"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(run_bodyrec({"detect", image, "--no-such-option"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", image, "--every", "two"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval", "nosuchstage"}).exit_code, 2);
  const RunResult version = run_bodyrec({"--version"});
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_FALSE(version.out.empty());
}

TEST(Cli, MalformedGroundTruthExitsThreeNamingFileAndLine) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  write_text(dir / "gt.xml", "<dataset>\n<frame number='0'>\n<objectlist>\n");
  RunResult r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt",
                             (dir / "gt.xml").string(), "--max-frames", "1", "-q"});
  expect_one_line_error(r, 3, (dir / "gt.xml").string());
  EXPECT_NE(r.err.find("line"), std::string::npos) << r.err;
  write_text(dir / "gt.txt", "1,1,10,10,5,5\n1,2,10,10\n");
  r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", (dir / "gt.txt").string(),
                   "--max-frames", "1", "-q"});
  expect_one_line_error(r, 3, (dir / "gt.txt").string() + ": line 2");
  r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", (dir / "missing.xml").string()});
  expect_one_line_error(r, 3, (dir / "missing.xml").string());
  // The source is checked too.
  write_text(dir / "good.txt", "1,1,10,10,5,5\n");
  r = run_bodyrec({"eval", "detect", "--source", (dir / "nothing.avi").string(), "--gt",
                   (dir / "good.txt").string()});
  expect_one_line_error(r, 3, (dir / "nothing.avi").string());
}

TEST(Cli, GlobWithMissingFolderIsAnInputError) {
  TempDir dir;
  const std::string pattern = (dir / "no-such-folder" / "*.png").string();
  expect_one_line_error(run_bodyrec({"detect", pattern}), 3, pattern);
}

TEST(Cli, UnwritableOutputExitsFour) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(0)));
  write_text(dir / "file", "x");
  const RunResult r = run_bodyrec({"detect", (dir / "a.png").string(), "--jsonl", (dir / "file" / "o.jsonl").string()});
  expect_one_line_error(r, 4, (dir / "file").string());
}

TEST(Cli, DetectOnImageGlobAndAnnotatedVideo) {
  TempDir dir;
  for (const char* name : {"f2.png", "f0.png", "f1.png", "f3.png"})
    cv::imwrite((dir / name).string(), cv::Mat(160, 120, CV_8UC3, cv::Scalar(40, 80, 120)));
  const auto jsonl = dir / "out.jsonl", video = dir / "out" / "a.avi";
  const RunResult r = run_bodyrec({"detect", (dir / "f*.png").string(), "--start", "1", "--every", "2", "--jsonl",
                                   jsonl.string(), "--annotate", video.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(read_text(jsonl));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(rows[0])["frame"].get<int>(), 1);
  EXPECT_EQ(nlohmann::json::parse(rows[1])["frame"].get<int>(), 3);
  cv::VideoCapture back(video.string());
  ASSERT_TRUE(back.isOpened());
  EXPECT_EQ(static_cast<int>(back.get(cv::CAP_PROP_FRAME_COUNT)), 2);
}

}  // namespace
}  // namespace bodyrec::testing
