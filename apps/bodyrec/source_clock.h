// The clock that a reid run's gallery times (first seen, last seen, scan and event times) follow.
// A recording or a video file: its own clock, so that "last seen" is when the person was last in the
// footage, not when bodyrec happened to process it. A live source (sensor, camera, --realtime) and an
// image folder: the wall clock at each write.
#pragma once

#include <optional>
#include <string>

#include "bodyrec/store/gallery_types.h"

namespace bodyrec::cli {

// When a file source's first frame was taken, from the file alone: its end is the file's modification
// time (a recording's meta.json is rewritten after its last frame; a video file is closed after its
// last frame) and its start is `duration_s` earlier. The start is moved back when needed so that the
// source's last frame is not after `now`: a gallery time is never in the future, so retention
// (`--prune-unseen-for`) counts from a real past moment. None when the file's time cannot be read.
std::optional<GalleryTime> file_source_start(const std::string& file, double duration_s, GalleryTime now);

}  // namespace bodyrec::cli
