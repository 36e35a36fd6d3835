#include "bodyrec/eval/role_metrics.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(RoleEvaluator, ThesisAccuracyCountsMissesAsWrong) {
  RoleEvaluator e(0.5);
  // Frame 1: leader right, member called non-member, non-member right, one labelled box missed.
  e.add_frame({{Box(0, 0, 10, 20), Role::kLeader},
               {Box(20, 0, 10, 20), Role::kMember},
               {Box(40, 0, 10, 20), Role::kNonMember},
               {Box(100, 0, 10, 20), Role::kMember}},
              {{Box(41, 0, 10, 20), Role::kNonMember},
               {Box(1, 0, 10, 20), Role::kLeader},
               {Box(20, 1, 10, 20), Role::kNonMember},
               {Box(300, 0, 10, 20), Role::kLeader}});
  // Frame 2: a potential member counts as a member.
  e.add_frame({{Box(0, 0, 10, 20), Role::kMember}}, {{Box(0, 0, 10, 20), Role::kPotentialMember}});
  const RoleScores s = e.scores();
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.boxes, 5);
  EXPECT_EQ(s.matched, 4);
  EXPECT_EQ(s.leader_correct, 1);
  EXPECT_EQ(s.member_correct, 2);
  EXPECT_DOUBLE_EQ(s.accuracy, 3.0 / 5);
  EXPECT_DOUBLE_EQ(s.accuracy_matched, 3.0 / 4);
  EXPECT_EQ(s.confusion.at("member").at("missed"), 1);
  EXPECT_EQ(s.confusion.at("member").at("non-member"), 1);
  EXPECT_EQ(s.confusion.at("member").at("member"), 1);
}

}  // namespace
}  // namespace bodyrec
