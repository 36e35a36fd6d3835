#include "bodyrec/groups/trajectory_roles.h"

#include <algorithm>
#include <cmath>

#include "bodyrec/core/error.h"

namespace bodyrec {

void TrajectoryRoleOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("TrajectoryRoleOptions", field, problem); };
  if (!(moving_speed >= 0)) fail("moving_speed", "must be >= 0");
  if (!(ahead_margin >= 0)) fail("ahead_margin", "must be >= 0");
  if (leader_hold < 1) fail("leader_hold", "must be >= 1 frame");
  if (!(velocity_span_s > 0)) fail("velocity_span_s", "must be > 0 s");
  if (!(energy_span_s > 0)) fail("energy_span_s", "must be > 0 s");
  if (confirm_frames < 1) fail("confirm_frames", "must be >= 1");
  if (!(leader_absence_s >= 0)) fail("leader_absence_s", "must be >= 0 s");
}

TrajectoryRoles::TrajectoryRoles(const TrajectoryRoleOptions& options) : options_(options) { options_.check(); }

cv::Point2d TrajectoryRoles::velocity(const History& h) const {
  if (h.positions.size() < 2) return {};
  const auto& [t0, p0] = h.positions.front();
  const auto& [t1, p1] = h.positions.back();
  return t1 > t0 ? (p1 - p0) * (1.0 / (t1 - t0)) : cv::Point2d();
}

double TrajectoryRoles::recent_energy(const History& h) const {
  double sum = 0;
  for (const auto& [t, e] : h.energy) sum += e;
  return h.energy.empty() ? 0.0 : sum / static_cast<double>(h.energy.size());
}

void TrajectoryRoles::forget(int id) { people_.erase(id); }

void TrajectoryRoles::hand_over_leader(int group, int to_id) {
  Lead& lead = leads_[group];
  lead.leader = to_id;
  lead.last_seen = people_.count(to_id) && !people_[to_id].positions.empty() ? people_[to_id].positions.back().first
                                                                              : lead.last_seen;
  lead.challenger = -1;
  lead.challenger_frames = 0;
}

TrajectoryRoleResult TrajectoryRoles::update(double t, const std::vector<TrajectoryInput>& people) {
  std::map<int, std::vector<const TrajectoryInput*>> groups;
  for (const auto& p : people) {
    History& h = people_[p.id];
    h.positions.emplace_back(t, p.ground);
    while (h.positions.size() > 2 && h.positions.front().first < t - options_.velocity_span_s) h.positions.pop_front();
    h.energy.emplace_back(t, p.motion_energy);
    while (h.energy.size() > 1 && h.energy.front().first < t - options_.energy_span_s) h.energy.pop_front();
    h.frames_in_group = p.group >= 0 && p.group == h.group ? h.frames_in_group + 1 : (p.group >= 0 ? 1 : 0);
    h.group = p.group;
    if (p.group >= 0) groups[p.group].push_back(&p);
  }

  TrajectoryRoleResult result;
  for (const auto& [group, members] : groups) {
    // Where the group goes, and who is furthest ahead that way.
    cv::Point2d centroid, v;
    for (const auto* m : members) {
      centroid += m->ground;
      v += velocity(people_[m->id]);
    }
    centroid *= 1.0 / static_cast<double>(members.size());
    v *= 1.0 / static_cast<double>(members.size());
    const double speed = std::hypot(v.x, v.y);
    auto score = [&](const TrajectoryInput* m) {
      if (speed >= options_.moving_speed) return (m->ground - centroid).dot(v * (1.0 / speed));
      return recent_energy(people_[m->id]);  // standing: who moves (gestures, sets off) most
    };
    const double margin = speed >= options_.moving_speed ? options_.ahead_margin : 0.0;
    const TrajectoryInput* best = *std::max_element(
        members.begin(), members.end(), [&](const auto* a, const auto* b) { return score(a) < score(b); });

    Lead& lead = leads_[group];
    const auto current = std::find_if(members.begin(), members.end(), [&](const auto* m) { return m->id == lead.leader; });
    if (current == members.end()) {
      // No leader yet, or it is missing (detector miss, occlusion): keep it for a while, else take the best.
      if (lead.leader < 0 || t - lead.last_seen > options_.leader_absence_s) lead = Lead{best->id, -1, 0, t};
    } else if (best->id != lead.leader && score(best) > score(*current) + margin) {
      lead.challenger_frames = best->id == lead.challenger ? lead.challenger_frames + 1 : 1;
      lead.challenger = best->id;
      if (lead.challenger_frames >= options_.leader_hold) lead = Lead{best->id, -1, 0, t};
    } else {
      lead.challenger = -1;
      lead.challenger_frames = 0;
    }
    if (std::any_of(members.begin(), members.end(), [&](const auto* m) { return m->id == lead.leader; }))
      lead.last_seen = t;
    result.leaders[group] = lead.leader;
  }
  for (auto it = leads_.begin(); it != leads_.end();)
    it = groups.count(it->first) ? std::next(it) : leads_.erase(it);

  for (const auto& p : people) {
    Role role = Role::kNonMember;
    if (p.group >= 0) {
      if (result.leaders[p.group] == p.id) role = Role::kLeader;
      else role = people_[p.id].frames_in_group >= options_.confirm_frames ? Role::kMember : Role::kPotentialMember;
    }
    result.roles[p.id] = role;
  }
  return result;
}

}  // namespace bodyrec
