#include "test_support.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return (v && *v) ? std::string(v) : fallback;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string source_dir() { return env_or("BODYREC_SOURCE_DIR", BODYREC_SOURCE_DIR_DEFAULT); }

std::string data_root_description() {
  const char* v = std::getenv("BODYREC_DATA");
  return (v && *v) ? std::string(v)
                   : "unset, tried " + (fs::path(source_dir()) / ".." / "shared" /
                                        "datasets").string();
}

fs::path data_root() {
  fs::path root = env_or("BODYREC_DATA", "");
  if (root.empty()) root = fs::path(source_dir()) / ".." / "shared" / "datasets";
  std::error_code ec;
  return fs::is_directory(root, ec) ? root : fs::path();
}

fs::path data_path(const std::string& relative) {
  const fs::path root = data_root();
  if (root.empty()) return {};
  const fs::path p = root / relative;
  std::error_code ec;
  return fs::exists(p, ec) ? p : fs::path();
}

fs::path vtest_path() { return "/usr/share/doc/opencv-doc/examples/data/vtest.avi"; }

RunResult run_bodyrec(const std::vector<std::string>& args, const std::vector<std::string>& prefix) {
  TempDir tmp;
  std::string cmd;
  for (const auto& p : prefix) cmd += shell_quote(p) + " ";
  cmd += shell_quote(env_or("BODYREC_BIN", BODYREC_BIN_DEFAULT));
  for (const auto& a : args) cmd += " " + shell_quote(a);
  cmd += " >" + shell_quote((tmp / "out").string()) + " 2>" + shell_quote((tmp / "err").string()) +
         " </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(tmp / "out");
  r.err = read_text(tmp / "err");
  return r;
}

TempDir::TempDir() {
  std::random_device rd;
  path_ = fs::temp_directory_path() /
          ("bodyrec-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json last_json_line(const std::string& out) {
  const auto end = out.find_last_not_of("\r\n");
  if (end == std::string::npos) return nlohmann::json();
  const auto newline = out.rfind('\n', end);
  const auto start = newline == std::string::npos ? 0 : newline + 1;
  return nlohmann::json::parse(out.substr(start, end + 1 - start));
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

size_t process_threads() {
  size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) n += entry.is_directory();
  return n;
}

void expect_one_line_error(const RunResult& r, int code, const std::string& names) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("bodyrec: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << "expected '" << names << "' in: " << r.err;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

const fs::path& synth_recording(const std::vector<std::string>& synth_args) {
  static TempDir dir;
  static std::map<std::vector<std::string>, fs::path> made;
  auto it = made.find(synth_args);
  if (it != made.end()) return it->second;
  const fs::path out = dir / ("rec" + std::to_string(made.size()));
  std::vector<std::string> args = {"synth"};
  args.insert(args.end(), synth_args.begin(), synth_args.end());
  args.insert(args.end(), {"--out", out.string(), "-q"});
  const RunResult r = run_bodyrec(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return made.emplace(synth_args, out).first->second;
}

}  // namespace bodyrec::testing
