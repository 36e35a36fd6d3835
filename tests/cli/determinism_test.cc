// The same input and options give the same output, byte for byte (HOG's parallel pyramid levels must not
// change the boxes).
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(Determinism, DetectTwiceGivesIdenticalMotFiles) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  for (const char* name : {"a.mot", "b.mot"}) {
    const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--start", "100", "--max-frames", "15",
                                     "--mot", (dir / name).string(), "--jsonl", (dir / "x.jsonl").string(), "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string a = read_text(dir / "a.mot");
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 15);
  EXPECT_EQ(a, read_text(dir / "b.mot"));
}

}  // namespace
}  // namespace bodyrec::testing
