// Gallery options of the commands that use a gallery (`gallery`, `reid`, `report`).
#pragma once

#include <chrono>
#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/store/gallery.h"  // parse_duration

namespace bodyrec::cli {

struct GalleryCliOptions {
  std::string path = "gallery.db";  // a file, or a postgresql:// URI (store/gallery.h)
};

// "--unseen-for" style durations; UsageError naming `option` when malformed.
std::chrono::seconds parse_retention(const std::string& text, const char* option);

// --gallery FILE|URI.
void add_gallery_path_option(CLI::App& sub, GalleryCliOptions& options);

}  // namespace bodyrec::cli
