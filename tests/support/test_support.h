// Helpers shared by the test programs: where the datasets are, running the `bodyrec` binary, temp dirs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec::testing {

// The datasets folder: $BODYREC_DATA, else ../shared/datasets beside the repository. Empty when absent.
std::filesystem::path data_root();

// A dataset sub-folder or file; empty path when it is absent.
std::filesystem::path data_path(const std::string& relative);

// Skips the current test with a message naming what is missing, when `relative` is not in the datasets.
#define BODYREC_REQUIRE_DATA(var, relative)                                                         \
  const std::filesystem::path var = ::bodyrec::testing::data_path(relative);                        \
  if (var.empty())                                                                                  \
  GTEST_SKIP() << "dataset " << (relative) << " not found under BODYREC_DATA ("                     \
               << ::bodyrec::testing::data_root_description() << ")"

std::string data_root_description();

// The repository root (to find tests/tools and fixtures).
std::string source_dir();

// vtest.avi from Debian's opencv-doc (installed by scripts/install-deps).
std::filesystem::path vtest_path();

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs build/bin/bodyrec with the given arguments (each shell-quoted), capturing stdout and stderr.
// `prefix` (e.g. a command that drops privileges) is put before it, each word shell-quoted.
RunResult run_bodyrec(const std::vector<std::string>& args, const std::vector<std::string>& prefix = {});

// A fresh empty directory under the system temp dir, removed at destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

std::string read_text(const std::filesystem::path& path);

// The last non-empty line of a command's stdout, parsed as JSON (the `--json` summary).
nlohmann::json last_json_line(const std::string& out);

bool contains(const std::string& text, const std::string& part);

// The lines of `text` (without their newlines).
std::vector<std::string> lines_of(const std::string& text);

// Threads of this process (Linux: one entry per thread in /proc/self/task): to check that code starts no
// thread pool of its own.
size_t process_threads();

// A failed command as the README promises: exit `code`, exactly one line on stderr starting with
// "bodyrec: error: " and containing `names` (the file, frame or field at fault).
void expect_one_line_error(const RunResult& r, int code, const std::string& names);

// Runs `f` and returns the message of the `Error` it throws ("" and a test failure when nothing or
// something else is thrown).
template <typename Error, typename F>
std::string thrown_message(F f, const char* expected) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected " << expected << ", got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected " << expected << ", nothing thrown";
  return "";
}
template <typename F>
std::string input_error(F parse) { return thrown_message<InputError>(parse, "InputError"); }
template <typename F>
std::string usage_error(F f) { return thrown_message<UsageError>(f, "UsageError"); }
void write_text(const std::filesystem::path& path, const std::string& text);

// A synthetic recording made once per test program with `bodyrec synth SYNTH_ARGS --out DIR -q` in a
// temporary directory that lives until the program ends; the same arguments give the same directory.
const std::filesystem::path& synth_recording(const std::vector<std::string>& synth_args);

}  // namespace bodyrec::testing
