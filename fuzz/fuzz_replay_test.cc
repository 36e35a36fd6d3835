// Replays every seed (fuzz/corpus/<target>) and every kept finding (fuzz/regressions/<target>) through its
// fuzz target, built with the normal compiler, so CI exercises the fuzz inputs without clang: a target
// must return 0 and let only bodyrec's typed errors through (it catches those itself).
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "fuzz_targets.h"
#include "test_support.h"

namespace bodyrec::fuzz {

// Test names and failure messages show the target's name, not its bytes.
void PrintTo(const NamedTarget& target, std::ostream* os) { *os << target.name; }

namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class FuzzReplay : public ::testing::TestWithParam<NamedTarget> {};

TEST_P(FuzzReplay, EveryCorpusAndRegressionInputGivesOnlyTypedErrors) {
  const NamedTarget target = GetParam();
  int replayed = 0;
  for (const char* folder : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(testing::source_dir()) / "fuzz" / folder / target.name;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      const std::string data = bytes_of(entry.path());
      SCOPED_TRACE(entry.path().string());
      int result = -1;
      EXPECT_NO_THROW(result = target.function(reinterpret_cast<const uint8_t*>(data.data()), data.size()));
      EXPECT_EQ(result, 0);
      ++replayed;
    }
  }
  // Every target has hand-written seeds; an empty folder means the corpus went missing.
  EXPECT_GT(replayed, 0) << "no inputs for fuzz target " << target.name;
}

TEST(FuzzTargets, EmptyAndGarbageInputGiveOnlyTypedErrors) {
  const std::string garbage("\0\xff<{\"[\n\r 1e999 nan -1", 20);
  for (const auto& t : all_targets()) {
    SCOPED_TRACE(t.name);
    EXPECT_EQ(t.function(nullptr, 0), 0);
    EXPECT_EQ(t.function(reinterpret_cast<const uint8_t*>(garbage.data()), garbage.size()), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(AllTargets, FuzzReplay, ::testing::ValuesIn(all_targets()),
                         [](const ::testing::TestParamInfo<NamedTarget>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace bodyrec::fuzz
