#include "bodyrec/groups/roles.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

RoleInput person(int id, double x, double energy = 0.1) { return {id, Box(x, 100, 30, 80), energy}; }

TEST(Roles, NamesRoundTrip) {
  for (Role r : {Role::kUnknown, Role::kMember, Role::kNonMember, Role::kLeader, Role::kPotentialMember})
    EXPECT_EQ(parse_role(to_string(r)), r);
  EXPECT_EQ(parse_role("Non_Member"), Role::kNonMember);
  EXPECT_EQ(parse_role("guide"), std::nullopt);
}

TEST(ThesisRoles, TransitoryLeaderMembersAndPasserBy) {
  ThesisRoles roles({}, false);
  // Frame 0: everyone moves (transitory). The motion box covers people 1 and 2; 1 moves most -> leader.
  // Person 2 overlaps the motion box and is 10 px from the leader -> member. Person 3 is 300 px away.
  auto r = roles.update(0, {person(1, 100, 0.3), person(2, 140, 0.2), person(3, 470, 0.2)}, Box(90, 90, 100, 100));
  EXPECT_EQ(r.at(1), Role::kLeader);
  EXPECT_EQ(r.at(2), Role::kMember);
  EXPECT_EQ(r.at(3), Role::kNonMember);
  // Tags are permanent: later the passer-by walks into the motion box and next to the group; it stays a
  // non-member. A newcomer next to the members joins them (overlaps a member's box, True Member check).
  r = roles.update(1, {person(1, 102), person(2, 142), person(3, 190), person(4, 160)}, Box(90, 90, 150, 100));
  EXPECT_EQ(r.at(1), Role::kLeader);
  EXPECT_EQ(r.at(3), Role::kNonMember);
  EXPECT_EQ(r.at(4), Role::kMember);
  EXPECT_EQ(roles.leader(), 1);
}

TEST(ThesisRoles, NoLeaderBeforeMotionOverlapsSomeone) {
  ThesisRoles roles({}, false);
  auto r = roles.update(0, {person(1, 100, 0.3), person(2, 400, 0.3)}, Box(250, 0, 20, 20));
  EXPECT_EQ(r.at(1), Role::kUnknown);
  EXPECT_EQ(r.at(2), Role::kUnknown);
  EXPECT_FALSE(roles.leader());
  r = roles.update(1, {person(1, 100, 0.3), person(2, 400, 0.3)}, Box(390, 90, 50, 50));
  EXPECT_EQ(r.at(2), Role::kLeader);
  EXPECT_EQ(r.at(1), Role::kNonMember);  // overlaps neither the motion box nor a member
}

TEST(ThesisRoles, StationaryPotentialMembersThenLeader) {
  ThesisRoles roles({}, false);
  // Nobody moves at the start: stationary. 1 and 2 stand 20 px apart; 3 stands alone.
  auto r = roles.update(0, {person(1, 100, 0), person(2, 150, 0), person(3, 500, 0)}, std::nullopt);
  EXPECT_EQ(r.at(1), Role::kPotentialMember);
  EXPECT_EQ(r.at(2), Role::kPotentialMember);
  EXPECT_EQ(r.at(3), Role::kUnknown);
  // Person 2 gestures: the motion box overlaps it -> leader; 1 member; 3 non-member.
  r = roles.update(1, {person(1, 100, 0), person(2, 150, 0.2), person(3, 500, 0)}, Box(150, 100, 20, 20));
  EXPECT_EQ(r.at(2), Role::kLeader);
  EXPECT_EQ(r.at(1), Role::kMember);
  EXPECT_EQ(r.at(3), Role::kNonMember);
}

TEST(ThesisRoles, StillBoxesArePrunedEvery25Frames) {
  ThesisRoles roles({}, false);
  for (int f = 0; f <= 25; ++f) {
    // Person 1 (leader) and 2 walk; 9 is a still false positive (a bin) with an unchanged box.
    const auto r = roles.update(f, {person(1, 100 + 2 * f, 0.3), person(2, 140 + 2 * f, 0.2), person(9, 600, 0)},
                                Box(90 + 2 * f, 90, 100, 100));
    if (f < 25) EXPECT_EQ(r.count(9), 1u) << f;
    else EXPECT_EQ(r.count(9), 0u);
  }
  EXPECT_TRUE(roles.pruned(9));
  EXPECT_FALSE(roles.pruned(1));
  EXPECT_FALSE(roles.pruned(2));
}

TEST(ThesisRoles, VotingChangesRolesEvery50Frames) {
  ThesisRoleOptions o;
  o.vote_period = 50;
  ThesisRoles roles(o, true);
  // Frames 0-50: the motion box sits on person 1 -> per-frame leader 1; 2 is far -> non-member.
  for (int f = 0; f <= 50; ++f) roles.update(f, {person(1, 100 + f, 0.3), person(2, 400 + f, 0.1)}, Box(100 + f, 100, 30, 80));
  auto r = roles.update(51, {person(1, 151, 0.3), person(2, 451, 0.1)}, Box(451, 100, 30, 80));
  EXPECT_EQ(r.at(1), Role::kLeader);  // voted role holds until the next vote
  EXPECT_EQ(r.at(2), Role::kNonMember);
  // Frames 52-101: the motion is on person 2 -> per-frame leader 2; at the vote 2 becomes the leader.
  for (int f = 52; f <= 101; ++f) r = roles.update(f, {person(1, 151, 0.0), person(2, 400 + f, 0.3)}, Box(400 + f, 100, 30, 80));
  EXPECT_EQ(r.at(2), Role::kLeader);
  EXPECT_EQ(r.at(1), Role::kNonMember);
  EXPECT_EQ(roles.leader(), 2);
}

TEST(ThesisRoles, HandOverMovesTheLeaderRole) {
  ThesisRoles roles({}, false);
  roles.update(0, {person(1, 100, 0.3)}, Box(100, 100, 30, 30));
  roles.hand_over_leader(1, 7);
  EXPECT_EQ(roles.leader(), 7);
  const auto r = roles.update(1, {person(7, 104, 0.3)}, Box(100, 100, 30, 30));
  EXPECT_EQ(r.at(7), Role::kLeader);
}

TEST(ThesisRoles, RejectsBadOptions) {
  ThesisRoleOptions o;
  o.vote_period = 0;
  EXPECT_THROW(ThesisRoles(o, true), UsageError);
}

}  // namespace
}  // namespace bodyrec
