// Scoring of online re-identification against a recording's truth (`bodyrec eval reid-stream`).
//
// Per-frame accuracy as the thesis counts it: body-frames whose assigned user is the right one, over
// body-frames with a true person (a body still undecided counts wrong). "The right one": users and
// identities are paired one to one, greedily by the body-frames they share, so a person's second user
// (a split) and a user's second person (a merge) count wrong.
// Enrolment errors, counted over tracks (a track is one body from entering to leaving; it gets at most
// one user, and its identity is the one most of its body-frames show):
//   splits = for every identity, the users its tracks got beyond the first (one person, two users);
//   merges = for every user, the identities of its tracks beyond the first (two people, one user).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct ReidStreamScore {
  double accuracy = 0;
  int frames = 0;      // body-frames with a true person
  int correct = 0, undecided = 0;
  int splits = 0, merges = 0;
  int users = 0, identities = 0, tracks = 0;
};

class ReidStreamCounter {
 public:
  // One body in one frame: its true identity, its track and the user assigned to it (none yet).
  void add(int identity, uint64_t track, std::optional<int64_t> user);
  // A decision seen as an event (enrolled / recognised) for a track: counts for splits and merges even
  // when the track never showed the user in a frame (decided as it left).
  void assign(uint64_t track, int64_t user);
  ReidStreamScore score() const;

 private:
  struct TrackStats {
    std::map<int, int> identities;  // identity -> body-frames
    std::optional<int64_t> user;
  };
  std::map<uint64_t, TrackStats> tracks_;
  std::map<int64_t, std::map<int, int>> user_frames_;  // user -> identity -> body-frames
  std::set<int> identities_;
  int frames_ = 0, undecided_ = 0;
};

// Which ground-truth box each body's box is (footage scored against a file of boxes and ids): the one-to-one
// pairing of largest total IoU over pairs with IoU >= min_iou. Returns, per body, an index into `truth` or
// -1 when it has none.
std::vector<int> match_bodies_to_truth(const std::vector<Box>& bodies, const std::vector<Box>& truth, double min_iou);

}  // namespace bodyrec
