// Checks made before long runs so that a bad output path fails at once, not after minutes of training.
#pragma once

#include <filesystem>
#include <string>

#include "bodyrec/core/error.h"

namespace bodyrec::cli {

// Throws ProcessingError naming `path` when its folder does not exist.
inline void require_output_folder(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw ProcessingError("cannot write " + path + ": folder " + parent.string() + " does not exist");
}

}  // namespace bodyrec::cli
