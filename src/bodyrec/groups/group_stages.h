// The group-leader stages after tracking (thesis Ch4): motion -> group membership -> roles -> leader
// tracking -> leader direction, one call per frame. Data flows one way: tracks in, a GroupFrame out.
// GroupPipeline (group_pipeline.h) runs detection and tracking before them.
//
// Role modes (RoleMode):
//  - kGroups (default): groups from trajectories (GroupMembership, on the ground plane when a
//    GroundPlane is given, else in pixels scaled by an estimated pixels-per-metre), one leader per group
//    (TrajectoryRoles), a DSST leader tracker and a direction per group.
//  - kThesis: Table 4.1 with permanent tags; kVoting: the 50-frame voting variant. Both have one
//    group (id 1: the leader and its members) as in the thesis.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/detection/differential_motion.h"
#include "bodyrec/groups/group_membership.h"
#include "bodyrec/groups/leader_direction.h"
#include "bodyrec/groups/leader_tracker.h"
#include "bodyrec/groups/roles.h"
#include "bodyrec/groups/trajectory_roles.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/io/ground_plane.h"
#include "bodyrec/tracking/tracker.h"

namespace bodyrec {

enum class RoleMode { kGroups, kThesis, kVoting };
const char* to_string(RoleMode mode);                          // "groups", "thesis", "voting"
std::optional<RoleMode> parse_role_mode(const std::string& text);  // the inverse

struct GroupStagesOptions {
  RoleMode roles = RoleMode::kGroups;
  DifferentialMotionOptions motion;
  ThesisRoleOptions thesis;
  TrajectoryRoleOptions trajectory;
  GroupOptions membership;
  LeaderTrackerOptions leader;
  LeaderDirectionOptions direction;
  double pixels_per_metre = 0;   // without a ground plane; 0 = from the first boxes (a person is 1.7 m)
  void check() const;            // throws UsageError naming the field
};

struct PersonView {
  int id = -1;
  Box box;
  TrackState state = TrackState::kConfirmed;
  Role role = Role::kUnknown;
  int group = -1;                        // -1: in no group
  double motion_energy = 0;              // fraction of the box's pixels that moved
  std::optional<cv::Point2d> ground;     // metres on the ground plane (when one is given)
};

struct LeaderView {
  int group = -1;
  LeaderStatus status;
  std::optional<Direction> direction;
};

// Milliseconds spent per stage on this frame.
struct StageTimes {
  double motion = 0, groups = 0, roles = 0, leader = 0, flow = 0;
};

struct GroupFrame {
  std::vector<PersonView> people;   // sorted by id
  std::vector<LeaderView> leaders;  // sorted by group
  bool motion_valid = false;
  std::optional<Box> motion_box;
  double motion_deviation = 0;
  StageTimes ms;
};

class GroupStages {
 public:
  // `ground` may be null (work in pixels). Calls options.check().
  GroupStages(const GroupStagesOptions& options, std::shared_ptr<const GroundPlane> ground);
  ~GroupStages();
  // One frame at time `t_seconds` (increasing) with the tracker's reported tracks for it.
  GroupFrame process(const cv::Mat& image, double t_seconds, const std::vector<TrackedPerson>& tracks);
  const GroupStagesOptions& options() const { return options_; }
  double pixels_per_metre() const { return pixels_per_metre_; }

 private:
  struct Leader {
    LeaderTracker tracker;
    LeaderDirection direction;
    int last_id = -1;
  };
  // Set roles and groups in `out`; return group id -> leader id.
  std::map<int, int> assign_thesis(GroupFrame& out, int frame_index);
  std::map<int, int> assign_groups(GroupFrame& out, double t);
  void track_leaders(GroupFrame& out, const std::vector<TrackedPerson>& tracks, const std::map<int, int>& leaders);

  GroupStagesOptions options_;
  std::shared_ptr<const GroundPlane> ground_;
  DifferentialMotion motion_;
  std::optional<ThesisRoles> thesis_;
  std::optional<GroupMembership> membership_;
  TrajectoryRoles trajectory_;
  std::map<int, Leader> leaders_;  // by group id
  std::map<int, int> last_seen_;   // track id -> frame counter, to forget ended tracks
  cv::Mat grey_, previous_grey_;
  double pixels_per_metre_ = 0;
  int frames_ = 0;
};

}  // namespace bodyrec
