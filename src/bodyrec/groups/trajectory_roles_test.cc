#include "bodyrec/groups/trajectory_roles.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(TrajectoryRoles, LeaderWalksAheadInTheDirectionOfTravel) {
  TrajectoryRoles roles;
  TrajectoryRoleResult r;
  // Group 5: person 1 walks 1 m ahead of person 2, both at 1.2 m/s along +x. Person 3 is alone.
  for (int f = 0; f < 20; ++f) {
    const double t = f / 7.0, x = 1.2 * t;
    r = roles.update(t, {{1, {x + 1.0, 0}, 0.1, 5}, {2, {x, 0.3}, 0.1, 5}, {3, {10 - x, 5}, 0.1, -1}});
  }
  EXPECT_EQ(r.leaders.at(5), 1);
  EXPECT_EQ(r.roles.at(1), Role::kLeader);
  EXPECT_EQ(r.roles.at(2), Role::kMember);
  EXPECT_EQ(r.roles.at(3), Role::kNonMember);
}

TEST(TrajectoryRoles, NewMemberIsPotentialUntilConfirmed) {
  TrajectoryRoleOptions o;
  o.confirm_frames = 3;
  TrajectoryRoles roles(o);
  TrajectoryRoleResult r;
  for (int f = 0; f < 3; ++f) {
    r = roles.update(f / 7.0, {{1, {f * 0.2 + 1, 0}, 0.1, 1}, {2, {f * 0.2, 0}, 0.1, 1}});
    EXPECT_EQ(r.roles.at(2), f < 2 ? Role::kPotentialMember : Role::kMember) << f;
  }
}

TEST(TrajectoryRoles, LeadChangesOnlyAfterTheHoldPeriod) {
  TrajectoryRoleOptions o;
  o.leader_hold = 5;
  TrajectoryRoles roles(o);
  TrajectoryRoleResult r;
  int f = 0;
  for (; f < 10; ++f) r = roles.update(f / 7.0, {{1, {f * 0.2 + 1, 0}, 0.1, 1}, {2, {f * 0.2, 0}, 0.1, 1}});
  ASSERT_EQ(r.leaders.at(1), 1);
  // Person 2 overtakes by 1 m: leader for the first 4 frames is still 1, then 2.
  for (int k = 0; k < 6; ++k, ++f) {
    r = roles.update(f / 7.0, {{1, {f * 0.2 + 1, 0}, 0.1, 1}, {2, {f * 0.2 + 2, 0}, 0.1, 1}});
    EXPECT_EQ(r.leaders.at(1), k < 4 ? 1 : 2) << k;
  }
}

TEST(TrajectoryRoles, StandingGroupLedByWhoMovesMost) {
  TrajectoryRoles roles;
  TrajectoryRoleResult r;
  for (int f = 0; f < 10; ++f)
    r = roles.update(f / 7.0, {{1, {0, 0}, 0.01, 2}, {2, {0.5, 0}, 0.2, 2}, {3, {1, 0}, 0.02, 2}});
  EXPECT_EQ(r.leaders.at(2), 2);
}

TEST(TrajectoryRoles, MissingLeaderKeepsTheLeadForAWhile) {
  TrajectoryRoleOptions o;
  o.leader_absence_s = 1.0;
  TrajectoryRoles roles(o);
  TrajectoryRoleResult r;
  int f = 0;
  for (; f < 10; ++f) r = roles.update(f / 7.0, {{1, {f * 0.2 + 1, 0}, 0.1, 1}, {2, {f * 0.2, 0}, 0.1, 1}, {3, {f * 0.2, 1}, 0.1, 1}});
  ASSERT_EQ(r.leaders.at(1), 1);
  // The leader's track is missing: for 1 s (7 frames) the lead stays with 1, then passes on.
  for (int k = 0; k < 9; ++k, ++f) {
    r = roles.update(f / 7.0, {{2, {f * 0.2, 0}, 0.1, 1}, {3, {f * 0.2, 1}, 0.1, 1}});
    if (k < 7) EXPECT_EQ(r.leaders.at(1), 1) << k;
    else EXPECT_NE(r.leaders.at(1), 1) << k;
  }
}

}  // namespace
}  // namespace bodyrec
