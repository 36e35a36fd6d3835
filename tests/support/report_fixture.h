// A small groups run for the report tests: a JSONL file as `bodyrec groups` writes it and a matching
// video of flat magenta frames (a colour nothing else on the page uses, so a screenshot shows whether
// the embedded images rendered); a small re-identification run and a gallery of two users whose scans
// are cyan bodies (another colour of their own).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "bodyrec/store/gallery.h"
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

// 30 rows of a `bodyrec reid` run: track 7 is user 1 from frame 5 (enrolled there), track 8 is never
// identified. User 2 has no event in the run.
inline void write_reid_run(const std::filesystem::path& path) {
  std::string text;
  for (int f = 0; f < 30; ++f) {
    nlohmann::json row = {{"frame", f}, {"time", f / 10.0}, {"events", nlohmann::json::array()}};
    row["bodies"] = {{{"track", 7}, {"user", f >= 5 ? nlohmann::json(1) : nlohmann::json()}, {"view", "F"},
                      {"box", {10, 20, 40, 100}}},
                     {{"track", 8}, {"user", nullptr}, {"view", nullptr}, {"box", {100, 20, 40, 100}}}};
    if (f == 5) row["events"].push_back({{"kind", "enrolled"}, {"user", 1}, {"track", 7}, {"view", "F"}, {"score", nullptr}});
    row["ms"] = {{"orient", 1.5}, {"match", 2.5}};
    text += row.dump() + "\n";
  }
  write_text(path, text);
}

// BGR of the gallery scans' bodies.
inline const cv::Scalar kScanCyan(255, 255, 0);

// A 128 x 64 scan of `view`: a cyan elliptic body on black, the ellipse as its mask.
inline GalleryScan cyan_scan(View view, GalleryTime time) {
  GalleryScan scan;
  scan.view = view;
  scan.image = cv::Mat::zeros(128, 64, CV_8UC3);
  scan.mask = cv::Mat::zeros(128, 64, CV_8UC1);
  cv::ellipse(scan.image, cv::Point(32, 64), cv::Size(26, 58), 0, 0, 360, kScanCyan, cv::FILLED);
  cv::ellipse(scan.mask, cv::Point(32, 64), cv::Size(26, 58), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  scan.features = cv::Mat(1, 64, CV_32F, cv::Scalar(1));
  scan.descriptor = "test";
  scan.time = time;
  return scan;
}

// 2026-11-20T13:00:00Z: the gallery fixture's first enrolment.
inline const GalleryTime kGalleryT0 = from_unix_ms(1795179600000LL);

// A gallery at `path`: user 1 "alice" with views F (enrolled 13:00), SR (13:01) and B (13:02), recognised
// at 13:05 (score 0.87); user 2 "bob" with BL only (enrolled 13:10). `images` false: stored without pixels.
inline void write_gallery(const std::filesystem::path& path, bool images = true) {
  GalleryOptions options;
  options.create = true;
  options.store_images = images;
  Gallery gallery(path.string(), options);
  const auto at = [](int minutes) { return kGalleryT0 + std::chrono::minutes(minutes); };
  const UserId alice = gallery.enrol(cyan_scan(View::F, at(0)), "alice", 7, "fixture");
  gallery.put_scan(alice, cyan_scan(View::SR, at(1)));
  gallery.put_scan(alice, cyan_scan(View::B, at(2)));
  Event seen;
  seen.user = alice;
  seen.kind = EventKind::kRecognised;
  seen.score = 0.87;
  seen.view = View::F;
  seen.time = at(5);
  gallery.log_event(seen);
  gallery.enrol(cyan_scan(View::BL, at(10)), "bob", 8, "fixture");
}

// `bodyrec report` of the fixture's reid run with its gallery (both written into `dir` when missing),
// into `dir / out`, with `extra` arguments (e.g. --no-images).
inline RunResult report_with_gallery(const TempDir& dir, const std::string& out,
                                     const std::vector<std::string>& extra = {}) {
  if (!std::filesystem::exists(dir / "reid.jsonl")) write_reid_run(dir / "reid.jsonl");
  if (!std::filesystem::exists(dir / "g.db")) write_gallery(dir / "g.db");
  std::vector<std::string> args = {"report", (dir / "reid.jsonl").string(), "--gallery", (dir / "g.db").string(),
                                   "--out", (dir / out).string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_bodyrec(args);
}

}  // namespace bodyrec::testing
