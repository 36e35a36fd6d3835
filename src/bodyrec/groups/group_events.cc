#include "bodyrec/groups/group_events.h"

#include <algorithm>
#include <map>

namespace bodyrec {

namespace {

std::map<int, std::vector<int>> groups_of(const GroupFrame& f) {
  std::map<int, std::vector<int>> groups;
  for (const PersonView& p : f.people)
    if (p.group >= 0) groups[p.group].push_back(p.id);
  for (auto& [group, members] : groups) std::sort(members.begin(), members.end());
  return groups;
}

// Group id -> the tracked leader's track id (groups whose leader is not being tracked are absent).
std::map<int, const LeaderView*> tracked_leaders(const GroupFrame& f) {
  std::map<int, const LeaderView*> leaders;
  for (const LeaderView& l : f.leaders)
    if (l.status.state == LeaderState::kTracking && l.status.track_id >= 0) leaders[l.group] = &l;
  return leaders;
}

}  // namespace

const char* group_event_name(GroupEventKind kind) {
  switch (kind) {
    case GroupEventKind::kLeaderLost: return "leader_lost";
    case GroupEventKind::kGroupDissolved: return "group_dissolved";
    case GroupEventKind::kGroupFormed: return "group_formed";
    case GroupEventKind::kLeaderFound: return "leader_found";
  }
  return "?";
}

std::vector<GroupEvent> group_events(const GroupFrame& before, const GroupFrame& now) {
  const auto groups_before = groups_of(before), groups_now = groups_of(now);
  const auto leaders_before = tracked_leaders(before), leaders_now = tracked_leaders(now);
  std::vector<GroupEvent> out;
  for (const auto& [group, was] : leaders_before) {
    const auto is = leaders_now.find(group);
    if (is != leaders_now.end()) continue;  // still tracked (a hand-over is a leader_found)
    GroupEvent e;
    e.kind = GroupEventKind::kLeaderLost;
    e.group = group;
    e.leader = was->status.track_id;
    const LeaderView* still = nullptr;
    for (const LeaderView& l : now.leaders)
      if (l.group == group) still = &l;
    if (!groups_now.count(group)) {
      e.reason = "dissolved";
    } else if (still && !still->status.lost_reason.empty()) {
      e.reason = still->status.lost_reason;
    } else {
      e.reason = "lost";
    }
    out.push_back(e);
  }
  for (const auto& [group, members] : groups_before)
    if (!groups_now.count(group)) out.push_back({GroupEventKind::kGroupDissolved, group, members, {}, {}, {}});
  for (const auto& [group, members] : groups_now)
    if (!groups_before.count(group)) out.push_back({GroupEventKind::kGroupFormed, group, members, {}, {}, {}});
  for (const auto& [group, is] : leaders_now) {
    const auto was = leaders_before.find(group);
    if (was != leaders_before.end() && was->second->status.track_id == is->status.track_id) continue;
    GroupEvent e;
    e.kind = GroupEventKind::kLeaderFound;
    e.group = group;
    e.leader = is->status.track_id;
    if (was != leaders_before.end()) e.previous = was->second->status.track_id;
    const auto members = groups_now.find(group);
    if (members != groups_now.end()) e.members = members->second;
    out.push_back(e);
  }
  return out;
}

}  // namespace bodyrec
