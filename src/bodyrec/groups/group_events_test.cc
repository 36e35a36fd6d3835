#include "bodyrec/groups/group_events.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

PersonView person(int id, int group) {
  PersonView p;
  p.id = id;
  p.group = group;
  return p;
}

LeaderView leader(int group, int track, LeaderState state, const std::string& reason = "") {
  LeaderView l;
  l.group = group;
  l.status.track_id = track;
  l.status.state = state;
  l.status.lost_reason = reason;
  return l;
}

std::string describe(const std::vector<GroupEvent>& events) {
  std::string s;
  for (const GroupEvent& e : events) {
    s += std::string(group_event_name(e.kind)) + " g" + std::to_string(e.group);
    if (e.leader) s += " leader " + std::to_string(*e.leader);
    if (e.previous) s += " after " + std::to_string(*e.previous);
    if (!e.reason.empty()) s += " (" + e.reason + ")";
    if (!e.members.empty()) {
      s += " [";
      for (size_t i = 0; i < e.members.size(); ++i) s += (i ? " " : "") + std::to_string(e.members[i]);
      s += "]";
    }
    s += "; ";
  }
  return s;
}

TEST(GroupEvents, AGroupFormsGetsALeaderHandsItOverLosesItAndDissolves) {
  GroupFrame empty, formed, led, handed, lost, gone;
  formed.people = {person(1, 0), person(3, 0), person(2, -1)};
  led = formed;
  led.leaders = {leader(0, 3, LeaderState::kTracking)};
  handed = formed;
  handed.leaders = {leader(0, 1, LeaderState::kTracking)};
  lost = formed;
  lost.leaders = {leader(0, 1, LeaderState::kLost, "weak peak")};
  gone.people = {person(1, -1), person(3, -1)};

  EXPECT_EQ(describe(group_events(empty, formed)), "group_formed g0 [1 3]; ");
  EXPECT_EQ(describe(group_events(formed, formed)), "");
  EXPECT_EQ(describe(group_events(formed, led)), "leader_found g0 leader 3 [1 3]; ");
  EXPECT_EQ(describe(group_events(led, led)), "");
  EXPECT_EQ(describe(group_events(led, handed)), "leader_found g0 leader 1 after 3 [1 3]; ");
  EXPECT_EQ(describe(group_events(handed, lost)), "leader_lost g0 leader 1 (weak peak); ");
  EXPECT_EQ(describe(group_events(lost, lost)), "");
  EXPECT_EQ(describe(group_events(lost, gone)), "group_dissolved g0 [1 3]; ");
}

TEST(GroupEvents, InOneFrameLossesComeBeforeDissolutionsAndFormationsBeforeNewLeaders) {
  GroupFrame before, after;
  before.people = {person(1, 0), person(2, 0), person(5, 4), person(6, 4)};
  before.leaders = {leader(0, 1, LeaderState::kTracking), leader(4, 6, LeaderState::kTracking)};
  after.people = {person(1, 0), person(2, 0), person(7, 9), person(8, 9)};
  after.leaders = {leader(0, 1, LeaderState::kTracking), leader(9, 8, LeaderState::kTracking)};
  EXPECT_EQ(describe(group_events(before, after)),
            "leader_lost g4 leader 6 (dissolved); group_dissolved g4 [5 6]; group_formed g9 [7 8]; "
            "leader_found g9 leader 8 [7 8]; ");
  // The end of a run: everything ends.
  EXPECT_EQ(describe(group_events(after, GroupFrame{})),
            "leader_lost g0 leader 1 (dissolved); leader_lost g9 leader 8 (dissolved); group_dissolved g0 [1 2]; "
            "group_dissolved g9 [7 8]; ");
}

TEST(GroupEvents, ALeaderWithoutATrackOrNotTrackedIsNoLeader) {
  GroupFrame before, after;
  before.people = after.people = {person(1, 0), person(2, 0)};
  before.leaders = {leader(0, -1, LeaderState::kTracking)};
  after.leaders = {leader(0, 2, LeaderState::kNone)};
  EXPECT_EQ(describe(group_events(before, after)), "");
  GroupFrame lost_without_reason = after;
  lost_without_reason.leaders = {};
  GroupFrame tracked = after;
  tracked.leaders = {leader(0, 2, LeaderState::kTracking)};
  EXPECT_EQ(describe(group_events(tracked, lost_without_reason)), "leader_lost g0 leader 2 (lost); ");
}

}  // namespace
}  // namespace bodyrec
