// Gallery options shared by the commands that write a gallery (`bodyrec reid`) and `bodyrec gallery`.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/store/gallery.h"

namespace bodyrec::cli {

struct GalleryCliOptions {
  std::string path = "gallery.db";
  bool no_images = false;
  std::string prune_unseen_for;  // "" = keep everyone
};

// "--unseen-for" style durations; UsageError naming `option` when malformed.
std::chrono::seconds parse_retention(const std::string& text, const char* option);

// --gallery FILE only (inspection commands).
void add_gallery_path_option(CLI::App& sub, GalleryCliOptions& options);
// --gallery, --no-images, --prune-unseen-for DURATION (commands that enrol people).
void add_gallery_write_options(CLI::App& sub, GalleryCliOptions& options);

// Opens (creating when missing) the gallery for enrolment: store_images from --no-images, then applies
// the retention time when given (forgets users unseen for that long; prints what it erased on stderr).
// UsageError for a malformed duration.
std::unique_ptr<Gallery> open_gallery_for_enrolment(const GalleryCliOptions& options);

}  // namespace bodyrec::cli
