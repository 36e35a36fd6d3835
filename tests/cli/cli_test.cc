// The command line as a user meets it: help, usage errors, input errors, and the outputs of `detect`.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

void expect_one_line_error(const RunResult& r, int code, const std::string& names) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("bodyrec: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
}

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
  EXPECT_EQ(run_bodyrec({"nosuchcommand"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--every", "0"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--preset", "fast"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"detect", vtest_path().string(), "--scale", "0.9"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval", "detect", "--source", vtest_path().string()}).exit_code, 2);  // no --gt
}

TEST(Cli, InputErrorsExitThreeNamingThePath) {
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
    EXPECT_EQ(row["frame"].get<int>(), static_cast<int>(i));
    EXPECT_NEAR(row["time"].get<double>(), i / 10.0, 1e-9);  // vtest.avi is 10 fps
    for (const auto& d : row["detections"]) {
      ASSERT_EQ(d["box"].size(), 4u);
      EXPECT_TRUE(d["score"].is_number());
      ++detections;
    }
  }
  EXPECT_GT(detections, 3);
  int mot_rows = 0;
  for (const auto& line : lines_of(read_text(mot))) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 9) << line;
    const int frame = std::stoi(line.substr(0, line.find(',')));
    EXPECT_GE(frame, 1);
    EXPECT_LE(frame, 3);
    ++mot_rows;
  }
  EXPECT_EQ(mot_rows, detections);
  for (const char* name : {"000000.png", "000001.png", "000002.png"})
    EXPECT_FALSE(cv::imread((frames / name).string()).empty()) << name;
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
  const auto rows = lines_of(read_text(jsonl));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(rows[1])["frame"].get<int>(), 1);
}

TEST(Cli, JsonlGoesToStdoutByDefault) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(200, 150, CV_8UC3, cv::Scalar(0, 0, 0)));
  const RunResult r = run_bodyrec({"detect", (dir / "a.png").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["detections"].size(), 0u);
}

}  // namespace
}  // namespace bodyrec::testing
