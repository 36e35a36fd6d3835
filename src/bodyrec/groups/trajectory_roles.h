// bodyrec's default role assignment: groups from trajectories (group_membership.h) and, in each group,
// a leader who walks ahead in the direction of travel or, while the group stands, who initiates motion.
// Everyone outside a group is a non-member, so passers-by are never called members (the thesis's
// program called every box a member on vtest.avi). Several groups at once, each with its own leader.
#pragma once

#include <deque>
#include <map>
#include <optional>
#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/groups/roles.h"

namespace bodyrec {

struct TrajectoryRoleOptions {
  double moving_speed = 0.3;    // m/s: a group moving at least this fast has a direction of travel
  double ahead_margin = 0.25;   // m: a challenger must be this much further ahead than the leader ...
  int leader_hold = 7;          // ... for this many frames in a row to take the lead (hysteresis)
  double velocity_span_s = 1.0; // seconds of history for a person's velocity
  double energy_span_s = 2.0;   // seconds of motion energy history for "who moves first"
  int confirm_frames = 5;       // frames in a group before someone is a member (before: potential member)
  double leader_absence_s = 3.0;  // a leader missing from its group this long loses the lead
  void check() const;
};

// One person on one frame as this logic sees it. `ground` in metres (or pixels / pixels-per-metre).
struct TrajectoryInput {
  int id = -1;
  cv::Point2d ground;
  double motion_energy = 0;
  int group = -1;  // from GroupMembership::group_of(), -1 when alone
};

struct TrajectoryRoleResult {
  std::map<int, Role> roles;        // every input id
  std::map<int, int> leaders;       // group id -> leader's track id (possibly not among this frame's people)
};

class TrajectoryRoles {
 public:
  explicit TrajectoryRoles(const TrajectoryRoleOptions& options = {});  // calls options.check()
  TrajectoryRoleResult update(double t_seconds, const std::vector<TrajectoryInput>& people);
  // The leader of `group` is now `to_id` (re-acquired under a new track id).
  void hand_over_leader(int group, int to_id);
  void forget(int id);

 private:
  struct History {
    std::deque<std::pair<double, cv::Point2d>> positions;
    std::deque<std::pair<double, double>> energy;
    int frames_in_group = 0;
    int group = -1;
  };
  struct Lead {
    int leader = -1;
    int challenger = -1;
    int challenger_frames = 0;
    double last_seen = 0;  // when the leader was last among the group's people
  };
  cv::Point2d velocity(const History& h) const;
  double recent_energy(const History& h) const;

  TrajectoryRoleOptions options_;
  std::map<int, History> people_;
  std::map<int, Lead> leads_;  // by group id
};

}  // namespace bodyrec
