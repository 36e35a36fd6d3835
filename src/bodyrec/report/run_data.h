// What a report is made of, as plain structs: the rows of a run's JSONL (a groups run or a
// re-identification run), evaluation summaries, gallery users and decoded key frames. Parsers turn text
// into these structs; the renderer (report.h) only sees structs, so it is testable without files.
#pragma once

#include <array>
#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec::report {

// Per-stage milliseconds of one frame, in the order the JSONL gives them.
using StageTimes = std::vector<std::pair<std::string, double>>;

// --- groups run (`bodyrec groups --jsonl`) ---
struct GroupsPerson {
  int id = 0;
  Box box;
  std::string role;  // leader, member, non-member, potential-member (or "potential member")
  int group = -1;
  std::string state;
};
struct GroupsLeader {
  int id = -1, group = -1;
  std::string state;                  // tracking, lost, ...
  std::optional<Box> box;             // while tracking
  std::optional<double> degrees;      // walking direction: 0 = image right, 90 = up, counter-clockwise
  double magnitude = 0;               // flow magnitude (pixels per frame)
};
struct GroupsFrameRow {
  int frame = 0;
  double time = 0;
  std::vector<GroupsPerson> people;
  std::vector<GroupsLeader> leaders;
  StageTimes ms;
};

// --- re-identification run (`bodyrec reid`) ---
struct ReidBody {
  int track = 0;
  std::optional<int> user;  // nullopt = not identified yet
  std::string view;         // "F".."BL" or "" when unknown
  Box box;
};
struct ReidEvent {
  std::string kind;  // enrolled, recognised, view_added, left
  std::optional<int> user;
  int track = -1;
  std::string view;
  std::optional<double> score;
};
struct ReidFrameRow {
  int frame = 0;
  double time = 0;
  std::vector<ReidBody> bodies;
  std::vector<ReidEvent> events;
  StageTimes ms;
  bool end = false;  // "end": true, the line after the last frame with the run's closing events: not a frame
  // Live runs (a sensor, a camera, --realtime): when the frame came and when its line was written (Unix
  // seconds), and the frames dropped so far because processing fell behind.
  std::optional<double> arrival, wall;
  std::optional<long> dropped;
};

enum class RunKind { kGroups, kReid };
const char* to_string(RunKind kind);

struct RunData {
  std::string name;  // the file the rows came from
  RunKind kind = RunKind::kGroups;
  std::vector<GroupsFrameRow> groups;  // when kind == kGroups
  std::vector<ReidFrameRow> reid;      // when kind == kReid
  int frame_count() const;  // frames processed: the rows, less a re-identification run's end row
};

// Reads a run's JSON lines. The kind comes from the rows ("people" = groups, "bodies" = re-id).
// Throws InputError "NAME:LINE: ..." on a malformed line, a missing field or a change of kind, and
// "NAME: no JSON rows" when there is nothing.
RunData parse_run(std::istream& in, const std::string& name);
RunData read_run(const std::string& path);

// --- evaluations (`bodyrec eval ... --json`, last stdout line) ---
enum class EvalKind { kReid, kReidStream, kGroups, kLandmarks, kLandmarkErrors, kTrack, kDetect, kRoles, kSegment };
const char* to_string(EvalKind kind);

struct EvalResult {
  std::string name;       // the file it came from
  EvalKind kind = EvalKind::kGroups;
  nlohmann::json summary;                 // the JSON object (empty for kLandmarkErrors)
  std::vector<double> cmc;                // kReid: rank-1..N matching rates
  std::vector<double> errors_rel_height;  // kLandmarkErrors: per-person error / box height
  std::vector<double> errors_px;          // kLandmarkErrors: per-person error in pixels
};

// Parses an eval result: either text whose last non-empty line is the JSON summary (kind from its keys),
// or JSON lines of per-person landmark errors (`eval landmarks --per-person`, keys mean_px and
// rel_height). Throws InputError naming `name` (and the line) when neither.
EvalResult parse_eval(const std::string& text, const std::string& name);
EvalResult read_eval(const std::string& path);

// --- gallery users (read_gallery_users in gallery_users.h fills these from the store) ---
// Times are wall-clock, as the gallery keeps them: seconds since the Unix epoch, UTC.
struct ReportUserEvent {
  std::string kind;  // enrolled, recognised, view_added, scan_replaced, left
  double time = 0;
  std::string view;  // "" when none
  std::optional<double> score;
  std::optional<int64_t> track;
  std::string source;  // recording or camera; "" when unknown
};
struct ReportUser {
  int id = 0;
  std::string label;
  double first_seen = 0, last_seen = 0;
  // Both in reid/view.h kAllViews order. A view shows as a scan when its image is non-empty or
  // `scanned` says the gallery holds one without pixels (stored or read with --no-images).
  std::array<cv::Mat, 8> views;
  std::array<bool, 8> scanned{};
  std::vector<ReportUserEvent> events;  // oldest first
};

// A decoded (and annotated) frame of the source to show.
struct KeyFrame {
  int frame = 0;
  cv::Mat image;
  std::string caption;
};

}  // namespace bodyrec::report
