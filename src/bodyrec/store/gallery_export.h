// Exports everything the gallery holds about one user (the right of access): each view's image and
// mask as the stored PNG bytes, and user.json with the user, every scan's metadata and feature values,
// and the event history.
#pragma once

#include <string>

#include "bodyrec/store/gallery.h"

namespace bodyrec {

struct ExportReport {
  int scans = 0, images = 0, masks = 0, events = 0;
  std::vector<std::string> files;  // written, relative to the directory
};

// Writes <dir>/<VIEW>-image.png, <dir>/<VIEW>-mask.png (when stored) and <dir>/user.json, creating
// <dir> (mode 0700: the export is as sensitive as the gallery). Existing files of those names are
// overwritten. InputError for an unknown user; ProcessingError when a file cannot be written.
ExportReport export_user(Gallery& gallery, UserId user, const std::string& dir);

}  // namespace bodyrec
