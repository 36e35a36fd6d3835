// `bodyrec report`: one self-contained HTML page (inline CSS and SVG, images as data URIs, no scripts,
// nothing fetched) about a run: a groups run (role timeline, group sizes, leader direction rose, key
// frames, speed), a re-identification run (gallery users, events, identity strips, speed) and any
// evaluations given. Only the sections the inputs support are rendered.
#pragma once

#include <string>
#include <vector>

#include "bodyrec/report/run_data.h"

namespace bodyrec::report {

struct ReportInput {
  RunData run;
  std::string source;                // the run's input: video, images or recording ("" = unknown)
  std::string generated;             // date/time text for the header
  std::vector<EvalResult> evals;
  bool have_gallery = false;         // users below come from a gallery (even when it is empty)
  std::vector<ReportUser> users;
  std::vector<KeyFrame> key_frames;  // already annotated; empty = none decoded
  bool images = true;                // false: --no-images, no person pixels anywhere
};

struct Section {
  std::string id, title, html;
};

// The sections the inputs support, in page order (ids: header, roles, groups, directions, key-frames,
// users, live, events, identities, key-frames, speed, evaluations; key-frames after the run's own).
std::vector<Section> build_sections(const ReportInput& input);

// The whole page.
std::string render_report(const ReportInput& input);

// Frames worth showing from a run: up to `count`, spread over the run (at least run length / (2 count)
// frames apart), in frame order. A groups run favours frames with leaders tracked and many people; a
// re-identification run frames with identification events (recognised, enrolled) and many bodies.
std::vector<int> choose_key_frames(const RunData& run, int count = 5);

// Draws a groups row on `image` (BGR): boxes in role colours with ids, the leader's walking direction as
// an arrow, a caption.
void annotate_groups_frame(cv::Mat& image, const GroupsFrameRow& row);

// Draws a re-identification row on `image` (BGR): each body's box in its user's colour, labelled with the
// user and view ("user 3 F"; a grey "track 7" while undecided), and a caption.
void annotate_reid_frame(cv::Mat& image, const ReidFrameRow& row);

// Draws the row of `frame` of `run` (either kind) on `image` and returns the key frame's caption.
// REQUIRES: `run` has a row for `frame` (one that choose_key_frames chose).
std::string annotate_key_frame(cv::Mat& image, const RunData& run, int frame);

// CSS colours of the roles (the thesis's: leader blue, member green, non-member red, potential amber).
std::string role_colour(const std::string& role);

}  // namespace bodyrec::report
