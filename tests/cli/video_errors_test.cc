// A video that breaks mid-way: exit code 3, one line naming the file and frame, and every frame decoded
// before the break written out as complete JSON lines.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(VideoErrors, TruncatedVideoKeepsFramesProcessedSoFar) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  const auto video = dir / "truncated.avi";
  {
    std::ifstream in(vtest_path(), std::ios::binary);
    std::string head(2000000, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    std::ofstream(video, std::ios::binary).write(head.data(), in.gcount());
  }
  const auto jsonl = dir / "out.jsonl";
  // A single HOG level keeps the test quick; detection quality is not what is tested here.
  const RunResult r = run_bodyrec({"detect", video.string(), "--preset", "thesis", "--levels", "1", "--jsonl",
                                   jsonl.string(), "-q"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(video.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("frame 194"), std::string::npos) << r.err;

  std::istringstream lines(read_text(jsonl));
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    const auto row = nlohmann::json::parse(line);  // throws (fails the test) on a partial line
    EXPECT_EQ(row["frame"].get<int>(), count);
    ++count;
  }
  EXPECT_EQ(count, 194);
}

}  // namespace
}  // namespace bodyrec::testing
