// JSON views of gallery contents, shared by `bodyrec gallery list/show --json` and export (the user's
// right of access). Times are UTC ISO 8601 strings; views their short names (reid/view.h). `time` is the
// source's clock (when it happened in the recording); `created`, `stored` and `logged` the wall clock
// when the gallery wrote the row (`stored`/`logged` absent in rows written before schema 3).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "bodyrec/store/gallery_types.h"

namespace bodyrec {

// {"id", "label", "views": ["F", "SL"], "scans", "created", "first_seen", "last_seen"}
nlohmann::json user_to_json(const User& user);
// {"view", "quality", "image", "mask" (booleans: stored or not), "descriptor", "descriptor_version",
//  "features": "1x64 32F", "time", and when known "stored"}
nlohmann::json scan_to_json(const StoredScan& scan);
// {"id", "kind", "time", and when present "user", "view", "score", "track", "source", "sensor", "logged"}
nlohmann::json event_to_json(const Event& event);
// {"type": "32F", "rows", "cols", "channels", "values": [row-major numbers]}
nlohmann::json features_to_json(const cv::Mat& features);

// "1x64 32F" (rows x cols, OpenCV depth, "C3" suffix for several channels).
std::string describe_matrix(const cv::Mat& m);
// The views column of `gallery list`: each view's name or ".", padded to 2 characters, in thesis
// order, e.g. "F  FR .  .  SL B  .  .".
std::string views_column(const std::array<bool, kViewCount>& views);

}  // namespace bodyrec
