// A bad option value that only the library can judge is reported with the flag the user typed, not the
// library's field name (apps/bodyrec/option_error_text.h).
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(OptionErrors, NameTheFlagOfTheFieldAtFault) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "no " << vtest_path() << " (opencv-doc)";
  const std::string video = vtest_path().string();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const Case cases[] = {
      {{"detect", video, "--preset", "default", "--win-stride", "0"}, "--win-stride must be >= 1"},  // same name
      {{"groups", video, "--leader-min-psr", "-1"}, "--leader-min-psr must be >= 0"},               // struct prefix
      {{"groups", video, "--direction-window", "0"}, "--direction-window must be >= 1 frame"},
      {{"track", video, "--coast", "-1"}, "--coast must be >= 0"},  // a unit suffix (coast_frames)
  };
  for (const Case& c : cases) {
    const RunResult r = run_bodyrec(c.args);
    expect_one_line_error(r, 2, c.message);
    EXPECT_EQ(r.err.find("Options."), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace bodyrec::testing
