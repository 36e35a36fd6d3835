// Events of the group-leader pipeline for subscribers (issue 47, `groups --events`): what changed between
// two consecutive frames' results (GroupFrame, group_pipeline.h).
//  - group_formed:    a group id has people this frame and had none the frame before;
//  - group_dissolved: the other way round;
//  - leader_found:    a group's leader is tracked this frame and was not, or another track now leads
//                     it (then `previous` names the track that led before);
//  - leader_lost:     a group's leader was tracked the frame before and is not now (lost, or the group
//                     dissolved); `reason` is the tracker's ("weak peak", "left image"...) or "dissolved".
// Order within a frame: leader_lost, group_dissolved, group_formed, leader_found; by group id within
// each kind. Comparing a frame with an empty GroupFrame ends every group (the end of a run).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bodyrec/groups/group_pipeline.h"

namespace bodyrec {

enum class GroupEventKind { kLeaderLost, kGroupDissolved, kGroupFormed, kLeaderFound };
const char* group_event_name(GroupEventKind kind);  // "leader_lost", "group_dissolved", ...

struct GroupEvent {
  GroupEventKind kind = GroupEventKind::kGroupFormed;
  int group = -1;
  std::vector<int> members;      // track ids in the group (formed: now; dissolved: before), sorted
  std::optional<int> leader;     // leader_found/lost: the leading track
  std::optional<int> previous;   // leader_found: the track that led before a hand-over
  std::string reason;            // leader_lost
};

// The events from `before` (the previous frame's result, empty for the first frame) to `now`.
std::vector<GroupEvent> group_events(const GroupFrame& before, const GroupFrame& now);

}  // namespace bodyrec
