#include "bodyrec/eval/reid_stream_metrics.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(ReidStreamMetrics, PerfectRunWithAReturningPerson) {
  ReidStreamCounter c;
  for (int f = 0; f < 10; ++f) c.add(0, 100, 1), c.add(1, 200, 2);
  for (int f = 0; f < 5; ++f) c.add(0, 101, 1);  // person 0 comes back with a new track, recognised
  const ReidStreamScore s = c.score();
  EXPECT_EQ(s.frames, 25);
  EXPECT_EQ(s.correct, 25);
  EXPECT_DOUBLE_EQ(s.accuracy, 1.0);
  EXPECT_EQ(s.splits, 0);
  EXPECT_EQ(s.merges, 0);
  EXPECT_EQ(s.users, 2);
  EXPECT_EQ(s.identities, 2);
  EXPECT_EQ(s.tracks, 3);
}

TEST(ReidStreamMetrics, UndecidedFramesCountWrong) {
  ReidStreamCounter c;
  for (int f = 0; f < 3; ++f) c.add(0, 7, std::nullopt);
  for (int f = 0; f < 7; ++f) c.add(0, 7, 4);
  const ReidStreamScore s = c.score();
  EXPECT_EQ(s.undecided, 3);
  EXPECT_DOUBLE_EQ(s.accuracy, 0.7);
}

TEST(ReidStreamMetrics, ReturningPersonEnrolledAgainIsASplit) {
  ReidStreamCounter c;
  for (int f = 0; f < 10; ++f) c.add(0, 100, 1);
  for (int f = 0; f < 4; ++f) c.add(0, 101, 2);  // new user for the same person
  const ReidStreamScore s = c.score();
  EXPECT_EQ(s.splits, 1);
  EXPECT_EQ(s.merges, 0);
  // Identity 0 is user 1's: the 4 frames under the second user are wrong.
  EXPECT_EQ(s.correct, 10);
}

TEST(ReidStreamMetrics, TwoPeopleGivenOneUserIsAMergeAndTheMinorityIsWrong) {
  ReidStreamCounter c;
  for (int f = 0; f < 10; ++f) c.add(0, 100, 1);
  for (int f = 0; f < 6; ++f) c.add(1, 200, 1);  // person 1 recognised as user 1
  const ReidStreamScore s = c.score();
  EXPECT_EQ(s.merges, 1);
  EXPECT_EQ(s.splits, 0);
  EXPECT_EQ(s.correct, 10);
  EXPECT_DOUBLE_EQ(s.accuracy, 10.0 / 16.0);
}

TEST(ReidStreamMetrics, AUserDecidedAsTheTrackLeftStillCountsAsASplit) {
  ReidStreamCounter c;
  for (int f = 0; f < 10; ++f) c.add(0, 100, 1);
  for (int f = 0; f < 5; ++f) c.add(0, 101, std::nullopt);  // back, undecided in every frame
  c.assign(101, 2);                                          // enrolled as it left
  c.assign(999, 3);                                          // a track with no true person: ignored
  const ReidStreamScore s = c.score();
  EXPECT_EQ(s.splits, 1);
  EXPECT_EQ(s.tracks, 2);
  EXPECT_EQ(s.correct, 10);
}

TEST(ReidStreamMetrics, EmptyRunScoresZero) {
  const ReidStreamScore s = ReidStreamCounter().score();
  EXPECT_EQ(s.frames, 0);
  EXPECT_EQ(s.accuracy, 0.0);
}

}  // namespace
}  // namespace bodyrec
