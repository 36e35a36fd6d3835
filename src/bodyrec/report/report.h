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
  std::string source;                // the video the run came from ("" = unknown)
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
// users, events, identities, speed, evaluations).
std::vector<Section> build_sections(const ReportInput& input);

// The whole page.
std::string render_report(const ReportInput& input);

// Frames worth showing from a groups run: up to `count`, favouring frames with leaders tracked and many
// people, spread over the run (at least run length / (2 count) frames apart), in frame order.
std::vector<int> choose_key_frames(const RunData& run, int count = 5);

// Draws a groups row on `image` (BGR): boxes in role colours with ids, the leader's walking direction as
// an arrow, a caption.
void annotate_groups_frame(cv::Mat& image, const GroupsFrameRow& row);

// CSS colours of the roles (the thesis's: leader blue, member green, non-member red, potential amber).
std::string role_colour(const std::string& role);

}  // namespace bodyrec::report
