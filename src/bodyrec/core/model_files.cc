#include "bodyrec/core/model_files.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace fs = std::filesystem;

std::vector<std::string> model_directories() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("BODYREC_MODELS"); env && *env) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share" / "bodyrec" / "models");
#ifdef BODYREC_INSTALL_MODELS_DIR
  candidates.emplace_back(BODYREC_INSTALL_MODELS_DIR);
#endif
#ifdef BODYREC_SOURCE_MODELS_DIR
  candidates.emplace_back(BODYREC_SOURCE_MODELS_DIR);
#endif
  std::vector<std::string> out;
  for (const fs::path& dir : candidates) {
    if (!fs::is_directory(dir, ec)) continue;
    const std::string canonical = fs::weakly_canonical(dir, ec).string();
    bool seen = false;
    for (const auto& o : out) seen |= o == canonical;
    if (!seen) out.push_back(canonical);
  }
  return out;
}

std::optional<std::string> find_model_file(const std::string& name) {
  std::error_code ec;
  for (const std::string& dir : model_directories()) {
    const fs::path file = fs::path(dir) / name;
    if (fs::is_regular_file(file, ec)) return file.string();
  }
  return std::nullopt;
}

std::string require_model_file(const std::string& name, const std::string& hint) {
  if (auto file = find_model_file(name)) return *file;
  std::string searched;
  for (const std::string& dir : model_directories()) searched += (searched.empty() ? "" : ", ") + dir;
  throw InputError("model " + name + " not found (searched: " + (searched.empty() ? "no models directory" : searched) +
                   "; set BODYREC_MODELS to a directory holding it); " + hint);
}

}  // namespace bodyrec
