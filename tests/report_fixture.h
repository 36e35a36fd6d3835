// A small groups run for the report tests: a JSONL file as `bodyrec groups` writes it and a matching
// video of flat magenta frames (a colour nothing else on the page uses, so a screenshot shows whether
// the embedded images rendered).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "test_support.h"

namespace bodyrec::testing {

// `frames` rows; tracks 1 and 2 in every frame (2 becomes a member following leader 1 from frame 10),
// track 3 in frames 5..14 as a non-member; the leader walks right.
inline void write_groups_run(const std::filesystem::path& path, int frames) {
  std::string text;
  for (int f = 0; f < frames; ++f) {
    const bool grouped = f >= 10;
    nlohmann::json row = {{"frame", f}, {"time", f / 7.0}};
    row["people"] = nlohmann::json::array();
    row["people"].push_back({{"id", 1}, {"box", {40 + 2 * f, 60, 40, 110}}, {"state", "confirmed"},
                             {"role", grouped ? "leader" : "non-member"}, {"group", grouped ? 0 : -1}, {"motion", 0.2}});
    row["people"].push_back({{"id", 2}, {"box", {150, 70, 40, 110}}, {"state", "confirmed"},
                             {"role", grouped ? "member" : "potential-member"}, {"group", grouped ? 0 : -1},
                             {"motion", 0.1}});
    if (f >= 5 && f < 15)
      row["people"].push_back({{"id", 3}, {"box", {240, 50, 40, 110}}, {"state", "confirmed"},
                               {"role", "non-member"}, {"group", -1}, {"motion", 0.1}});
    row["leaders"] = nlohmann::json::array();
    if (grouped)
      row["leaders"].push_back({{"group", 0},
                                {"id", 1},
                                {"state", "tracking"},
                                {"box", {40 + 2 * f, 60, 40, 110}},
                                {"direction", {{"degrees", 10.0}, {"magnitude", 2.0}, {"samples", 5}}}});
    row["motion"] = {{"valid", true}, {"deviation", 5.0}};
    row["ms"] = {{"motion", 0.4}, {"groups", 0.1}, {"roles", 0.01}, {"leader", 3.0 + f % 3}, {"flow", 0.6}};
    text += row.dump() + "\n";
  }
  write_text(path, text);
}

// A 320x240 MJPG video of `frames` magenta frames.
inline void write_magenta_video(const std::filesystem::path& path, int frames) {
  cv::VideoWriter video(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 7, cv::Size(320, 240));
  for (int f = 0; f < frames; ++f) video.write(cv::Mat(240, 320, CV_8UC3, cv::Scalar(255, 0, 255)));
}

}  // namespace bodyrec::testing
