#include "output_paths.h"

#include <filesystem>
#include <string>
#include <system_error>

#include "bodyrec/core/error.h"

namespace bodyrec::cli {
namespace {

namespace fs = std::filesystem;

// Paths that many outputs may share: stdout and devices.
bool is_shareable(const std::string& value) {
  if (value.empty() || value == "-") return true;
  std::error_code ec;
  const fs::file_status s = fs::status(value, ec);
  return !ec && fs::exists(s) && !fs::is_regular_file(s) && !fs::is_directory(s);
}

bool same_path(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    return !ec && same;
  }
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec), cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && ca == cb;
}

void check_subtree(CLI::App& app) {
  // Commands set only their final callback(), which runs after this one.
  app.parse_complete_callback([&app] { check_output_paths(app); });
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) check_subtree(*sub);
}

}  // namespace

bool is_output_option(const CLI::Option& option) {
  for (const char* name : {"--jsonl", "--annotate", "--mot", "--out", "--events-spool"})
    if (option.check_lname(std::string(name).substr(2))) return true;
  return false;
}

void check_output_paths(const CLI::App& command) {
  const std::vector<const CLI::Option*> options = command.get_options([](const CLI::Option* o) { return o->count() > 0; });
  for (const CLI::Option* out : options) {
    if (!is_output_option(*out)) continue;
    for (const std::string& target : out->results()) {
      if (is_shareable(target)) continue;
      for (const CLI::Option* other : options) {
        for (const std::string& value : other->results()) {
          if (other == out || is_shareable(value) || !same_path(target, value)) continue;
          throw UsageError(out->get_name() + " " + target + " is also " + other->get_name() +
                           ": give the output another path (it would be overwritten)");
        }
      }
    }
  }
}

void check_output_paths_everywhere(CLI::App& app) { check_subtree(app); }

}  // namespace bodyrec::cli
