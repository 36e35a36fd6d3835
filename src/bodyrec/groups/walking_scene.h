// Walking-group scenes in the EWAP (BIWI) / UCY layout of OpenTraj: obsmat.txt trajectories and groups.txt
// labels. Used to evaluate and train trajectory-based group membership (issue 11).
#pragma once

#include <map>
#include <iosfwd>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

namespace bodyrec {

// One obsmat.txt row: `frame ped pos_x pos_z pos_y v_x v_z v_y` (metres, m/s; z is unused).
struct ObsmatRow {
  int frame = 0;
  int person = 0;
  cv::Point2d position;  // (pos_x, pos_y)
  cv::Point2d velocity;  // (v_x, v_y)
};

// Reads obsmat.txt: 8 blank-separated numbers per line (blank lines skipped); frame and person must be
// integers >= 0; every field finite. Throws InputError naming the file, the line and the field at fault,
// also when the file cannot be opened, holds no rows or repeats a (frame, person) pair.
std::vector<ObsmatRow> read_obsmat(const std::string& path);
// The same from a stream; `name` names the source in messages.
std::vector<ObsmatRow> read_obsmat(std::istream& in, const std::string& name);

// Reads groups.txt: one group per line, integer person ids separated by blanks; blank lines skipped;
// lines with one id are singletons and are kept. An id repeated on a line counts once, and an id may be
// on two lines (seq_eth has both: its lines 36-37 and 52/54 overlap), so a group file is a list of
// "walks together" sets, not a partition. Throws InputError naming the file and line for a non-integer
// or negative id.
std::vector<std::vector<int>> read_groups(const std::string& path);
// The same from a stream; `name` names the source in messages.
std::vector<std::vector<int>> read_groups(std::istream& in, const std::string& name);

// A scene: trajectories with times in seconds and the labelled groups.
struct WalkingScene {
  std::string name;                         // folder name, e.g. "seq_eth"
  double seconds_per_frame = 0;             // estimated from obsmat (see estimate_seconds_per_frame)
  std::vector<ObsmatRow> rows;              // sorted by frame, then person
  std::vector<std::vector<int>> groups;     // lines of 2+ distinct people only

  // True when both people are on one line of groups.txt.
  bool together(int a, int b) const;
};

// The video frame period, from the data itself: the median over consecutive samples of one person of
// |displacement| / (|velocity| * frame gap), over samples moving faster than 0.3 m/s. The EWAP/UCY
// files do not state their frame rate in a common place (eth: 15 fps, hotel and zara: 25 fps; all are
// annotated every 0.4 s). Samples whose ratio overflows (positions near the double range) are skipped.
// ENSURES: the result is finite and > 0. Throws InputError when fewer than 10 moving samples exist or
// their median ratio is 0.
double estimate_seconds_per_frame(const std::vector<ObsmatRow>& rows, const std::string& where);

// Reads DIR/obsmat.txt and DIR/groups.txt. Groups may name people absent from obsmat (kept: they score
// nothing). `seconds_per_frame` <= 0 means estimate it.
WalkingScene read_walking_scene(const std::string& dir, double seconds_per_frame = 0);

}  // namespace bodyrec
