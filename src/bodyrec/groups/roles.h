// Roles of the people a group-leader tracker sees (thesis Ch4, Table 4.1), and the thesis's two ways of
// assigning them from detection boxes and the motion box: permanent tags (`thesis`) and 50-frame voting
// (`voting`). bodyrec's default, trajectory-based assignment lives in trajectory_roles.h.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/core/role.h"

namespace bodyrec {

// One tracked person on one frame, as the role logic sees it.
struct RoleInput {
  int id = -1;
  Box box;
  double motion_energy = 0;  // fraction of the box's pixels that moved (DifferentialMotion::energy_in)
};

struct ThesisRoleOptions {
  double true_member_distance = 70;  // px: the True Member check's gap to an assigned box (author's code)
  double close_distance = 70;        // px: boxes this close are "significantly close" (stationary state)
  double moving_energy = 0.02;       // a box with this motion energy counts as moving (scene state)
  int prune_period = 25;             // frames between false-positive pruning passes
  double still_tolerance = 2;        // px: a box "did not change" when it moved less than this
  int vote_period = 50;              // voting variant: frames between votes
  void check() const;
};

// Table 4.1. Call update() once per frame with every reported track and the motion box (if valid).
//  - The scene state is decided on the first frame with people: transitory when at least half of them
//    move, else stationary.
//  - Transitory: the leader is the first box to overlap the motion box (most motion energy on ties);
//    then a box overlapping the motion box or a member's box becomes a member if it passes the True
//    Member check (overlaps an assigned box or lies within true_member_distance of one); every other box
//    becomes a non-member.
//  - Stationary: boxes within close_distance of another box are potential members; the leader is the
//    potential member that first overlaps the motion box; potential members then become members, the rest
//    non-members.
//  - Tags 1-3 are permanent (`thesis`); every prune_period frames a box whose position, accumulated
//    displacement and tag did not change over the period is dropped as a still false positive.
//  - `voting` (the thesis's "exponential motion" variant): the rules run afresh on every frame, each id's
//    per-frame roles are counted, and every vote_period frames the most frequent one becomes its role.
class ThesisRoles {
 public:
  ThesisRoles(const ThesisRoleOptions& options, bool voting);  // calls options.check()

  // Returns the role of every input id (pruned ids are absent).
  std::map<int, Role> update(int frame_index, const std::vector<RoleInput>& people, const std::optional<Box>& motion_box);

  // The leader moved to another track id (leader re-acquired under a new id): the new id takes the role.
  void hand_over_leader(int from_id, int to_id);
  std::optional<int> leader() const { return leader_; }
  bool pruned(int id) const { return pruned_.count(id) > 0; }

 private:
  struct Person {
    Role role = Role::kUnknown;
    Box box, box_at_check;
    double travelled = 0, travelled_at_check = 0;  // accumulated |dx| + |dy|
    Role role_at_check = Role::kUnknown;
    std::map<Role, int> votes;
  };
  // The thesis's rules applied to the people without a permanent role; `roles` holds the fixed ones.
  void assign(const std::vector<RoleInput>& people, const std::optional<Box>& motion_box,
              std::map<int, Role>& roles, std::optional<int>& leader);
  void prune(int frame_index);

  ThesisRoleOptions options_;
  bool voting_;
  enum class Scene { kUnknown, kTransitory, kStationary } scene_ = Scene::kUnknown;
  std::map<int, Person> people_;
  std::map<int, bool> pruned_;
  std::optional<int> leader_;
  int last_prune_ = -1, last_vote_ = -1;
};

}  // namespace bodyrec
