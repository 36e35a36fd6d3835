// Usage errors as the README promises them: exit 2 and one line `bodyrec: error: ...` naming the option and
// the value in plain words, whether the error comes from CLI11's parsing (unknown option, missing value,
// wrong type, out of range, not one of the choices) or from bodyrec's own checks; NaN and infinities are
// refused by every floating-point option of every command.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// Exit 2 and exactly the line "bodyrec: error: MESSAGE".
void expect_usage_error(const std::vector<std::string>& args, const std::string& message) {
  std::string command;
  for (const auto& a : args) command += " " + a;
  SCOPED_TRACE("bodyrec" + command);
  const RunResult r = run_bodyrec(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, "bodyrec: error: " + message + "\n");
  EXPECT_EQ(r.out, "");
}

// The commands of `bodyrec [PARENT] --help` ("Subcommands:" section).
std::vector<std::string> subcommands(const std::vector<std::string>& parent) {
  std::vector<std::string> args = parent;
  args.push_back("--help");
  const RunResult r = run_bodyrec(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> names;
  bool in_list = false;
  for (const std::string& line : lines_of(r.out)) {
    if (line == "Subcommands:") {
      in_list = true;
      continue;
    }
    std::smatch m;
    if (in_list && std::regex_match(line, m, std::regex(R"(  ([a-z][a-z0-9-]*)\s.*)"))) names.push_back(m[1]);
    else if (in_list && !line.empty() && line[0] != ' ') in_list = false;
  }
  return names;
}

// The first option of a command's --help whose type is FLOAT, and how many values it takes.
std::optional<std::pair<std::string, int>> first_float_option(const std::vector<std::string>& command) {
  std::vector<std::string> args = command;
  args.push_back("--help");
  const std::string help = run_bodyrec(args).out;
  std::smatch m;
  if (!std::regex_search(help, m, std::regex(R"(\n  (?:-\w,)?(--[a-z0-9-]+) FLOAT\S*( x (\d+))?)"))) return std::nullopt;
  return std::make_pair(std::string(m[1]), m[3].matched ? std::stoi(m[3]) : 1);
}

TEST(UsageErrors, NanAndInfinityAreRefusedByFloatOptions) {
  const std::string v = vtest_path().string();
  expect_usage_error({"detect", v, "--hit-threshold", "nan"}, "--hit-threshold: nan is not a finite number");
  expect_usage_error({"detect", v, "--scale", "inf"}, "--scale: inf is not a finite number");
  expect_usage_error({"track", v, "--nms-iou", "-inf"}, "--nms-iou: -inf is not a finite number");
  expect_usage_error({"reid", "rec", "--threshold", "nan"}, "--threshold: nan is not a finite number");
  expect_usage_error({"reid", "rec", "--threshold", "NaN"}, "--threshold: NaN is not a finite number");
  expect_usage_error({"groups", v, "--fhog-upsample", "1e999"}, "--fhog-upsample: 1e999 is not a finite number");
  // Options with a range refuse NaN too (every comparison with NaN is false, so a range check alone lets it in).
  expect_usage_error({"eval", "detect", "--source", v, "--gt", "gt.txt", "--iou", "nan"},
                     "--iou: nan is not a finite number");
  expect_usage_error({"eval", "orient", "rec", "--min-visible", "inf"}, "--min-visible: inf is not a finite number");
}

// Every command, the gallery's and eval's included.
std::vector<std::vector<std::string>> every_command() {
  std::vector<std::vector<std::string>> commands;
  for (const std::string& name : subcommands({})) {
    if (name == "eval" || name == "gallery") {
      for (const std::string& sub : subcommands({name})) commands.push_back({name, sub});
    } else {
      commands.push_back({name});
    }
  }
  return commands;
}

// Every command's first floating-point option given NaN (or +-inf).
TEST(UsageErrors, EveryCommandsFloatOptionsRefuseNan) {
  const std::vector<std::vector<std::string>> commands = every_command();
  ASSERT_GE(commands.size(), 25u);
  const char* values[] = {"nan", "inf", "-inf", "-nan"};
  int tried = 0;
  for (const auto& command : commands) {
    const auto option = first_float_option(command);
    if (!option) continue;
    std::vector<std::string> args = command;
    args.push_back(option->first);
    const std::string value = values[tried++ % 4];
    for (int i = 0; i < option->second; ++i) args.push_back(value);
    expect_usage_error(args, option->first + ": " + value + " is not a finite number");
  }
  EXPECT_GE(tried, 20);
}

// No --help shows an empty list as a default (CLI11's "=[]" for repeatable options such as --eval).
TEST(UsageErrors, HelpShowsNoEmptyListDefaults) {
  for (std::vector<std::string> command : every_command()) {
    command.push_back("--help");
    const RunResult r = run_bodyrec(command);
    EXPECT_EQ(r.exit_code, 0) << command[0];
    EXPECT_FALSE(contains(r.out, "=[]")) << command[0] << ":\n" << r.out;
  }
}

TEST(UsageErrors, RangeAndTypeErrorsAreReadable) {
  const std::string v = vtest_path().string();
  expect_usage_error({"detect", v, "--every", "0"}, "--every: 0 is not a positive number");
  expect_usage_error({"track", v, "--detect-every", "0"}, "--detect-every: 0 is not a positive number");
  expect_usage_error({"eval", "orient", "rec", "--min-visible", "1.5"}, "--min-visible: 1.5 is not in [0, 1]");
  expect_usage_error({"eval", "detect", "--source", v, "--gt", "gt.txt", "--iou", "0.01"},
                     "--iou: 0.01 is not in [0.05, 1]");
  expect_usage_error({"report", "run.jsonl", "--out", "r.html", "--key-frames", "13"}, "--key-frames: 13 is not in [0, 12]");
  expect_usage_error({"reid", "rec", "--max-events-per-user", "-1"},
                     "--max-events-per-user: -1 is not a non-negative number");
  expect_usage_error({"detect", v, "--every", "abc"}, "--every: abc is not a number");
  expect_usage_error({"detect", v, "--every", "2.5"}, "--every: 2.5 is not a whole number");
  expect_usage_error({"detect", v, "--max-frames", "99999999999"}, "--max-frames: 99999999999 is out of range");
  expect_usage_error({"detect", v, "--scale", "fast"}, "--scale: fast is not a number");
  expect_usage_error({"detect", v, "--preset", "fast"}, "--preset: 'fast' is not one of auto, default, photo, foreground, thesis, opencv");
  expect_usage_error({"detect", v, "--motion", "sometimes"}, "--motion: 'sometimes' is not one of on, off, preset");
  expect_usage_error({"track", v, "--kf-velocity-noise", "0"}, "--kf-velocity-noise: 0 is not a positive number");
  expect_usage_error({"track", v, "--local-margin", "5"}, "--local-margin must be in [0, 2]");
  expect_usage_error({"landmark", v, "--mask-threshold", "1e9"}, "--mask-threshold: 1e9 is not in [-20, 20]");
  expect_usage_error({"landmark", v, "--threshold-offsets", "0,100"}, "--threshold-offsets: 100 is not in [-20, 20]");
  // A dlib fHOG model is its own detector: HOG's settings given with it would be silently ignored.
  expect_usage_error({"detect", v, "--model", "people.svm", "--preset", "thesis"},
                     "a dlib fHOG model is its own detector: --preset takes no value with it");
  expect_usage_error({"detect", v, "--model", "people.svm", "--win-stride", "4"},
                     "--win-stride is a HOG option; a dlib fHOG model takes none");
  expect_usage_error({"track", v, "--model", "people.svm", "--motion", "on"},
                     "--motion is a HOG option; a dlib fHOG model takes none");
  expect_usage_error({"track", v, "--preset", "photo", "--local-height-margin", "0.2"},
                     "--local-height-margin is a HOG option; --preset photo uses the DPM detector");
  // detect searches no tracks: the local-search options are not its own.
  expect_usage_error({"detect", v, "--local-margin", "0.2"},
                     "unknown option --local-margin (see bodyrec detect --help)");
  expect_usage_error({"groups", v, "--seconds-per-frame", "0.1"},
                     "unknown option --seconds-per-frame (see bodyrec groups --help)");
  expect_usage_error({"landmark", v, "--detector", "hog", "--model", "people.svm"},
                     "--detector hog and --model/--detector-model people.svm name two detectors: give one");
  expect_usage_error({"landmark", v, "--local-margin", "0.2"}, "--local-margin requires --track");
  expect_usage_error({"groups", v, "--sensor-id", "hall"}, "--sensor-id names the sensor in MQTT events: it needs --events");
  expect_usage_error({"groups", v, "--roles", "bosses"}, "--roles: 'bosses' is not one of groups, thesis, voting");
  expect_usage_error({"orient", "rec", "--views", "best"}, "--views: 'best' is not one of robust, thesis");
}

TEST(UsageErrors, ParseErrorsAreOneLineInBodyrecsFormat) {
  const std::string v = vtest_path().string();
  expect_usage_error({"detect", v, "--bogus"}, "unknown option --bogus (see bodyrec detect --help)");
  expect_usage_error({"detect", v, "extra"}, "unexpected argument extra (see bodyrec detect --help)");
  expect_usage_error({"detect", v, "--every"}, "--every: missing value");
  expect_usage_error({"detect", v, "--roi", "10", "10"}, "--roi: expects 4 values, got 2");
  expect_usage_error({"report", "run.jsonl"}, "--out is required");
  const RunResult none = run_bodyrec({});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(none.err.rfind("bodyrec: error: a command is required (one of eval, detect, track,", 0), 0u)
      << none.err;
  const RunResult unknown = run_bodyrec({"frobnicate"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.err.rfind("bodyrec: error: unknown command 'frobnicate' (one of eval, detect,", 0), 0u)
      << unknown.err;
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  const RunResult eval = run_bodyrec({"eval", "frobnicate"});
  EXPECT_EQ(eval.exit_code, 2);
  EXPECT_EQ(eval.err.rfind("bodyrec: error: eval: unknown command 'frobnicate' (one of ", 0), 0u) << eval.err;
  // Help and version still exit 0 and print to stdout.
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{{"--help"}, {"detect", "--help"}, {"--version"}}) {
    const RunResult r = run_bodyrec(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(r.out.empty());
  }
}

TEST(UsageErrors, AnEmptyRoiIsAUsageError) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  for (const auto& [w, h] : std::vector<std::pair<std::string, std::string>>{{"0", "0"}, {"20", "0"}, {"-5", "40"}}) {
    const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--roi", "10", "10", w, h, "--max-frames", "1",
                                     "--jsonl", (dir / "d.jsonl").string(), "-q"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "bodyrec: error: --roi: " + w + "x" + h + " is not a region (width and height must be positive)\n");
    EXPECT_FALSE(fs::exists(dir / "d.jsonl"));
  }
  const RunResult ok = run_bodyrec({"detect", vtest_path().string(), "--roi", "10", "10", "300", "300", "--max-frames",
                                    "1", "--preset", "thesis", "--levels", "1", "-q"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

}  // namespace
}  // namespace bodyrec::testing
