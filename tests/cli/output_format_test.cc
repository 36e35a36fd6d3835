// What the outputs look like to someone reading them: JSON numbers with the digits they carry, progress
// only on a terminal, and the report's frame count of a re-identification run.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// Significant digits of a number as JSON writes it ("0.07856999999999999" has 16, "1733312345.0" 10).
int significant_digits(const std::string& text) {
  const std::string mantissa = text.substr(0, text.find_first_of("eE"));
  std::string digits;
  for (char c : mantissa)
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  digits.erase(0, digits.find_first_not_of('0'));
  if (mantissa.find('.') != std::string::npos && !digits.empty()) {
    // Trailing zeros after the point ("12.0") carry nothing.
    while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
  }
  return static_cast<int>(digits.size());
}

// Every floating-point number in a JSON line has at most 6 significant digits, or no fraction beyond its
// integer part.
void expect_short_numbers(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float()) {
    const std::string text = j.dump();
    const double magnitude = std::fabs(j.get<double>());
    const int integer_digits = magnitude >= 1 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
    EXPECT_LE(significant_digits(text), std::max(6, integer_digits)) << where << ": " << text;
  } else if (j.is_structured()) {
    for (const auto& item : j) expect_short_numbers(item, where);
  }
}

void expect_short_numbers_in_lines(const std::string& text, const std::string& where) {
  int lines = 0;
  for (const std::string& line : lines_of(text)) {
    if (line.empty() || line[0] != '{') continue;
    expect_short_numbers(nlohmann::json::parse(line), where);
    ++lines;
  }
  EXPECT_GT(lines, 0) << where;
}

TEST(OutputFormat, JsonNumbersCarrySixSignificantDigits) {
  EXPECT_EQ(significant_digits("0.07856999999999999"), 16);
  EXPECT_EQ(significant_digits("0.07857"), 4);
  EXPECT_EQ(significant_digits("1733312345.0"), 10);
  EXPECT_EQ(significant_digits("1.23457e-07"), 6);
  TempDir dir;
  const fs::path rec = synth_recording({"--frames", "4", "--people", "2", "--seed", "3", "--scenario", "group"});
  struct Case {
    std::vector<std::string> args;
    fs::path jsonl;  // "" = only stdout
  };
  std::vector<Case> cases = {
      {{"orient", rec.string(), "--jsonl", (dir / "o.jsonl").string(), "--json", "-q"}, dir / "o.jsonl"},
      {{"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string(), "--json"}, dir / "s.jsonl"},
      {{"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--jsonl", (dir / "r.jsonl").string(), "--json",
        "-q"},
       dir / "r.jsonl"},
      {{"eval", "orient", rec.string(), "--json"}, ""},
  };
  if (fs::exists(vtest_path())) {
    // vtest.avi runs at 10 frames per second: frame 3's time, 3 * 0.1, is 0.30000000000000004 as a double.
    const std::vector<std::string> fast = {"--preset", "thesis", "--levels", "2", "--max-frames", "4", "-q"};
    Case detect{{"detect", vtest_path().string(), "--jsonl", (dir / "d.jsonl").string()}, dir / "d.jsonl"};
    Case track{{"track", vtest_path().string(), "--jsonl", (dir / "t.jsonl").string()}, dir / "t.jsonl"};
    detect.args.insert(detect.args.end(), fast.begin(), fast.end());
    track.args.insert(track.args.end(), fast.begin(), fast.end());
    cases.push_back(detect);
    cases.push_back(track);
  }
  for (const Case& c : cases) {
    const std::string where = c.args[0] + " " + c.args[1];
    SCOPED_TRACE(where);
    const RunResult r = run_bodyrec(c.args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (!c.jsonl.empty()) expect_short_numbers_in_lines(read_text(c.jsonl), where + " JSONL");
    if (std::find(c.args.begin(), c.args.end(), "--json") != c.args.end())
      expect_short_numbers(last_json_line(r.out), where + " --json");
  }
  if (fs::exists(vtest_path())) {
    const auto lines = lines_of(read_text(dir / "d.jsonl"));
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(nlohmann::json::parse(lines[3])["time"].dump(), "0.3");
  }
  // The reader of these files still reads them: the report, and the AP tool (tests/tools/ap50.py) in
  // ApCrosscheck (cli_data_test).
  const RunResult report = run_bodyrec({"report", (dir / "r.jsonl").string(), "--out", (dir / "r.html").string()});
  EXPECT_EQ(report.exit_code, 0) << report.err;
}

TEST(OutputFormat, SynthDrawsNoProgressIntoAFile) {
  TempDir dir;
  // stderr is a file here (run_bodyrec captures it): no '\r' redraws, no progress lines.
  const RunResult r = run_bodyrec({"synth", "--frames", "60", "--people", "1", "--seed", "2", "--out",
                                   (dir / "rec").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(contains(r.out, "60 frames")) << r.out;
}

// `bodyrec reid` ends its JSONL with finish()'s events on a line marked "end": true; the report counts the
// recording's frames, not that line.
TEST(OutputFormat, ReportCountsTheFramesOfAReidRun) {
  TempDir dir;
  const fs::path rec = synth_recording({"--frames", "4", "--people", "2", "--seed", "3", "--scenario", "group"});
  RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--jsonl",
                             (dir / "r.jsonl").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(read_text(dir / "r.jsonl"));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_TRUE(nlohmann::json::parse(lines.back()).value("end", false));
  r = run_bodyrec({"report", (dir / "r.jsonl").string(), "--out", (dir / "r.html").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "re-identification run, 4 frames,")) << r.out;
  EXPECT_TRUE(contains(read_text(dir / "r.html"), "frames <b>4 (0–3,")) << r.out;
}

}  // namespace
}  // namespace bodyrec::testing
