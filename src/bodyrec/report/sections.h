// Section builders behind render_report (report.h), one per file by run kind.
#pragma once

#include <vector>

#include "bodyrec/report/report.h"

namespace bodyrec::report {

// Groups run: role timeline, group counts, leader direction rose, key frames.
void add_groups_sections(const ReportInput& input, std::vector<Section>& out);
// Re-identification run: live source, events timeline, identity strip per body, key frames.
void add_reid_sections(const ReportInput& input, std::vector<Section>& out);
// Key frames: the annotated frames decoded from --source, or which frames they would be (both run kinds).
Section key_frames_section(const ReportInput& input);
// Gallery users, one row of 8 views each (any run kind, when a gallery was given).
Section users_section(const ReportInput& input);
// Milliseconds per frame per stage (both run kinds).
void add_speed_section(const std::vector<StageTimes>& frames, std::vector<Section>& out);
// Evaluations: summary table, CMC curves, per-scene pair F1, landmark error histograms.
void add_eval_sections(const ReportInput& input, std::vector<Section>& out);

// A small categorical palette (CSS colours) for users and series; index wraps.
const char* palette(int index);

}  // namespace bodyrec::report
