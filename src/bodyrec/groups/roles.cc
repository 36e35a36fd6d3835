#include "bodyrec/groups/roles.h"

#include <algorithm>
#include <cmath>

#include "bodyrec/core/error.h"

namespace bodyrec {

void ThesisRoleOptions::check() const {
  if (!(true_member_distance >= 0)) throw UsageError("--true-member-distance must be >= 0");
  if (!(close_distance >= 0)) throw UsageError("--close-distance must be >= 0");
  if (!(moving_energy >= 0 && moving_energy <= 1)) throw UsageError("--moving-energy must be in 0..1");
  if (prune_period < 1) throw UsageError("--prune-period must be >= 1 frame");
  if (!(still_tolerance >= 0)) throw UsageError("--still-tolerance must be >= 0");
  if (vote_period < 1) throw UsageError("--vote-period must be >= 1 frame");
}

ThesisRoles::ThesisRoles(const ThesisRoleOptions& options, bool voting) : options_(options), voting_(voting) {
  options_.check();
}

namespace {

bool overlaps(const Box& a, const Box& b) { return (a & b).area() > 0; }

// The unassigned person overlapping the motion box with the most motion energy, if any.
std::optional<int> first_in_motion(const std::vector<RoleInput>& people, const std::map<int, Role>& roles,
                                   const std::optional<Box>& motion_box, bool potential_only) {
  std::optional<int> best;
  double best_energy = -1;
  if (!motion_box) return best;
  for (const auto& p : people) {
    const auto it = roles.find(p.id);
    const Role r = it == roles.end() ? Role::kUnknown : it->second;
    if (r != Role::kUnknown && r != Role::kPotentialMember) continue;
    if (potential_only && r != Role::kPotentialMember) continue;
    if (overlaps(p.box, *motion_box) && p.motion_energy > best_energy) {
      best = p.id;
      best_energy = p.motion_energy;
    }
  }
  return best;
}

bool in_group(Role r) { return r == Role::kLeader || r == Role::kMember; }

}  // namespace

void ThesisRoles::assign(const std::vector<RoleInput>& people, const std::optional<Box>& motion_box,
                         std::map<int, Role>& roles, std::optional<int>& leader) {
  auto role_of = [&](int id) {
    const auto it = roles.find(id);
    return it == roles.end() ? Role::kUnknown : it->second;
  };
  auto open = [&](int id) {
    const Role r = role_of(id);
    return r == Role::kUnknown || r == Role::kPotentialMember;
  };

  if (scene_ == Scene::kStationary) {
    // Transient tag: boxes significantly close to another box.
    for (const auto& p : people) {
      if (!open(p.id)) continue;
      for (const auto& q : people)
        if (q.id != p.id && box_gap(p.box, q.box) <= options_.close_distance) {
          roles[p.id] = Role::kPotentialMember;
          break;
        }
    }
    if (!leader) {
      leader = first_in_motion(people, roles, motion_box, true);
      if (leader) roles[*leader] = Role::kLeader;
    }
    if (!leader) return;  // potential members stay potential until someone leads
    for (const auto& p : people)
      if (open(p.id)) roles[p.id] = role_of(p.id) == Role::kPotentialMember ? Role::kMember : Role::kNonMember;
    return;
  }

  // Transitory state.
  if (!leader) {
    leader = first_in_motion(people, roles, motion_box, false);
    if (leader) roles[*leader] = Role::kLeader;
  }
  if (!leader) return;
  // Members join in chains (a box next to a new member may join too), so iterate to a fixed point.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& p : people) {
      if (!open(p.id)) continue;
      bool near_group = motion_box && overlaps(p.box, *motion_box);
      bool true_member = false;
      for (const auto& q : people) {
        if (q.id == p.id || !in_group(role_of(q.id))) continue;
        near_group = near_group || overlaps(p.box, q.box);
        true_member = true_member || box_gap(p.box, q.box) <= options_.true_member_distance;
      }
      if (near_group && true_member) {
        roles[p.id] = Role::kMember;
        changed = true;
      }
    }
  }
  for (const auto& p : people)
    if (open(p.id)) roles[p.id] = Role::kNonMember;
}

void ThesisRoles::prune(int frame_index) {
  const bool check = last_prune_ < 0 || frame_index - last_prune_ >= options_.prune_period;
  if (!check) return;
  for (auto& [id, person] : people_) {
    if (last_prune_ >= 0 && id != leader_ && person.role == person.role_at_check &&
        std::abs(person.box.x - person.box_at_check.x) < options_.still_tolerance &&
        std::abs(person.box.y - person.box_at_check.y) < options_.still_tolerance &&
        person.travelled - person.travelled_at_check < options_.still_tolerance)
      pruned_[id] = true;
    person.box_at_check = person.box;
    person.travelled_at_check = person.travelled;
    person.role_at_check = person.role;
  }
  last_prune_ = frame_index;
}

std::map<int, Role> ThesisRoles::update(int frame_index, const std::vector<RoleInput>& all_people,
                                        const std::optional<Box>& motion_box) {
  std::vector<RoleInput> people;
  for (const auto& p : all_people) {
    if (pruned(p.id)) continue;
    auto [it, fresh] = people_.try_emplace(p.id);
    Person& person = it->second;
    if (fresh) {
      person.box_at_check = p.box;
      person.role_at_check = Role::kUnknown;
    } else {
      person.travelled += std::abs(p.box.x - person.box.x) + std::abs(p.box.y - person.box.y);
    }
    person.box = p.box;
    people.push_back(p);
  }

  if (scene_ == Scene::kUnknown && !people.empty()) {
    const auto moving = std::count_if(people.begin(), people.end(),
                                      [&](const RoleInput& p) { return p.motion_energy >= options_.moving_energy; });
    scene_ = 2 * static_cast<size_t>(moving) >= people.size() ? Scene::kTransitory : Scene::kStationary;
  }

  std::map<int, Role> roles;
  if (!voting_) {
    for (const auto& p : people)
      if (people_[p.id].role != Role::kUnknown) roles[p.id] = people_[p.id].role;
    assign(people, motion_box, roles, leader_);
    for (const auto& [id, role] : roles)
      if (role != Role::kPotentialMember) people_[id].role = role;  // tags 1-3 are permanent
  } else {
    // Fresh per-frame roles, counted; every vote_period frames the most frequent becomes the role.
    std::optional<int> frame_leader;
    std::map<int, Role> raw;
    assign(people, motion_box, raw, frame_leader);
    if (last_vote_ < 0) last_vote_ = frame_index;
    for (const auto& p : people) {
      const Role r = raw.count(p.id) ? raw[p.id] : Role::kUnknown;
      people_[p.id].votes[r]++;
    }
    if (frame_index - last_vote_ >= options_.vote_period) {
      for (auto& [id, person] : people_) {
        if (person.votes.empty()) continue;
        const auto best = std::max_element(person.votes.begin(), person.votes.end(),
                                           [](const auto& a, const auto& b) { return a.second < b.second; });
        person.role = best->first;
        person.votes.clear();
      }
      last_vote_ = frame_index;
      leader_.reset();
      for (const auto& [id, person] : people_)
        if (person.role == Role::kLeader && !leader_) leader_ = id;
    }
    for (const auto& p : people) {
      const Role voted = people_[p.id].role;
      roles[p.id] = voted != Role::kUnknown ? voted : (raw.count(p.id) ? raw[p.id] : Role::kUnknown);
    }
    if (!leader_) leader_ = frame_leader;
  }
  for (const auto& p : people) roles.try_emplace(p.id, Role::kUnknown);
  prune(frame_index);
  for (auto it = roles.begin(); it != roles.end();)
    it = pruned(it->first) ? roles.erase(it) : std::next(it);
  return roles;
}

void ThesisRoles::hand_over_leader(int from_id, int to_id) {
  if (from_id == to_id) return;
  Person& to = people_[to_id];
  to.role = Role::kLeader;
  to.votes.clear();
  const auto from = people_.find(from_id);
  if (from != people_.end() && from->second.role == Role::kLeader) from->second.role = Role::kMember;
  leader_ = to_id;
}

}  // namespace bodyrec
