#include "bodyrec/eval/tracking_metrics.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

LabelledBox box(int frame, int id, Box b) {
  LabelledBox l;
  l.frame = frame;
  l.id = id;
  l.box = b;
  return l;
}

const Box kA(0, 0, 10, 20), kB(100, 0, 10, 20), kFar(300, 300, 10, 20);

TEST(TrackingEvaluator, PerfectTrackingScoresOne) {
  TrackingEvaluator e;
  for (int f = 0; f < 3; ++f) {
    const Box a(kA.x + f, 0, 10, 20), b(kB.x - f, 0, 10, 20);
    e.add_frame({box(f, 7, a), box(f, 9, b)}, {box(f, 1, a), box(f, 2, b)});
  }
  const TrackingScores s = e.scores();
  // 6 GT boxes, 6 matches at IoU 1, no errors: MOTA 1, MOTP 1; ids 1->7, 2->9 give IDTP 6: IDF1 1.
  EXPECT_EQ(s.ground_truth, 6);
  EXPECT_EQ(s.matches, 6);
  EXPECT_EQ(s.fp + s.fn + s.id_switches, 0);
  EXPECT_DOUBLE_EQ(s.mota, 1.0);
  EXPECT_DOUBLE_EQ(s.motp, 1.0);
  EXPECT_DOUBLE_EQ(s.idf1, 1.0);
  EXPECT_EQ(s.frames, 3);
}

TEST(TrackingEvaluator, OneIdentitySwitch) {
  TrackingEvaluator e;
  // One person over 4 frames; the tracker calls it 1, 1, then 2, 2.
  e.add_frame({box(0, 1, kA)}, {box(0, 5, kA)});
  e.add_frame({box(1, 1, kA)}, {box(1, 5, kA)});
  e.add_frame({box(2, 2, kA)}, {box(2, 5, kA)});
  e.add_frame({box(3, 2, kA)}, {box(3, 5, kA)});
  const TrackingScores s = e.scores();
  // CLEAR MOT: 4 matches, one switch at frame 2 -> MOTA = 1 - 1/4 = 0.75.
  EXPECT_EQ(s.id_switches, 1);
  EXPECT_EQ(s.fp, 0);
  EXPECT_EQ(s.fn, 0);
  EXPECT_DOUBLE_EQ(s.mota, 0.75);
  // IDF1: GT 5 pairs with track 1 (or 2): IDTP 2, IDFN 2, IDFP 2 -> 4 / (4 + 2 + 2) = 0.5.
  EXPECT_EQ(s.idtp, 2);
  EXPECT_EQ(s.idfp, 2);
  EXPECT_EQ(s.idfn, 2);
  EXPECT_DOUBLE_EQ(s.idf1, 0.5);
}

TEST(TrackingEvaluator, FalsePositivesAndMisses) {
  TrackingEvaluator e;
  // Frame 0: GT a, b; track on a (IoU 1) and a false track far away -> 1 FP, 1 FN.
  // Frame 1: GT a; track on a shifted by 2 px: IoU = 8*20 / (12*20) = 2/3 -> match.
  // Frame 2: GT a; track shifted by 6 px: IoU = 4*20 / (16*20) = 1/4 < 0.5 -> 1 FP and 1 FN.
  e.add_frame({box(0, 1, kA), box(0, 2, kFar)}, {box(0, 10, kA), box(0, 11, kB)});
  e.add_frame({box(1, 1, Box(2, 0, 10, 20))}, {box(1, 10, kA)});
  e.add_frame({box(2, 1, Box(6, 0, 10, 20))}, {box(2, 10, kA)});
  const TrackingScores s = e.scores();
  EXPECT_EQ(s.ground_truth, 4);
  EXPECT_EQ(s.fp, 2);
  EXPECT_EQ(s.fn, 2);
  EXPECT_EQ(s.id_switches, 0);
  EXPECT_EQ(s.matches, 2);
  // MOTA = 1 - (2 + 2 + 0) / 4 = 0; MOTP = (1 + 2/3) / 2 = 5/6.
  EXPECT_DOUBLE_EQ(s.mota, 0.0);
  EXPECT_NEAR(s.motp, 5.0 / 6.0, 1e-12);
  // IDF1: 4 track boxes, 4 GT boxes; GT 10 <-> track 1 overlap in frames 0, 1: IDTP 2.
  // IDF1 = 4 / (4 + 2 + 2) = 0.5.
  EXPECT_EQ(s.idtp, 2);
  EXPECT_DOUBLE_EQ(s.idf1, 0.5);
}

TEST(TrackingEvaluator, IdentityScoreDiffersFromMota) {
  // One person over 6 frames, tracked as id 1 for 3 frames and id 2 for the last 3.
  // CLEAR MOT: one switch (frame 3): MOTA = 1 - 1/6 = 5/6.
  // IDF1: GT 5 pairs with track 1 (or 2): IDTP 3, IDFP 3, IDFN 3 -> 6 / (6 + 3 + 3) = 1/2.
  TrackingEvaluator split;
  for (int f = 0; f < 6; ++f) split.add_frame({box(f, f < 3 ? 1 : 2, kA)}, {box(f, 5, kA)});
  TrackingScores s = split.scores();
  EXPECT_EQ(s.id_switches, 1);
  EXPECT_NEAR(s.mota, 5.0 / 6.0, 1e-12);
  EXPECT_EQ(s.idtp, 3);
  EXPECT_DOUBLE_EQ(s.idf1, 0.5);

  // Ids 1,1,2,2,1,1: two switches (frames 2 and 4): MOTA = 1 - 2/6 = 2/3. IDF1 prefers track 1 (4
  // frames): IDTP 4, IDFP 2, IDFN 2 -> 8 / 12 = 2/3: switching back is punished by MOTA, not by IDF1.
  TrackingEvaluator back;
  const int ids[6] = {1, 1, 2, 2, 1, 1};
  for (int f = 0; f < 6; ++f) back.add_frame({box(f, ids[f], kA)}, {box(f, 5, kA)});
  s = back.scores();
  EXPECT_EQ(s.id_switches, 2);
  EXPECT_NEAR(s.mota, 2.0 / 3.0, 1e-12);
  EXPECT_EQ(s.idtp, 4);
  EXPECT_NEAR(s.idf1, 2.0 / 3.0, 1e-12);
}

TEST(TrackingEvaluator, KeepsPreviousCorrespondenceOverBetterOverlap) {
  TrackingEvaluator e;
  // Frame 0: GT 1 at A matched to track 1 at A. Frame 1: track 1 shifted by 2 px (IoU 2/3) and track 2
  // exactly on A (IoU 1). CLEAR MOT keeps 1 <-> 1 (still >= 0.5): no switch, track 2 is a FP.
  e.add_frame({box(0, 1, kA)}, {box(0, 1, kA)});
  e.add_frame({box(1, 1, Box(2, 0, 10, 20)), box(1, 2, kA)}, {box(1, 1, kA)});
  const TrackingScores s = e.scores();
  EXPECT_EQ(s.id_switches, 0);
  EXPECT_EQ(s.fp, 1);
  EXPECT_NEAR(s.mota, 0.5, 1e-12);  // 1 - 1/2
}

TEST(TrackingEvaluator, IgnoredTruthNeitherHitNorMiss) {
  TrackingEvaluator e;
  LabelledBox ignored = box(0, 3, kB);
  ignored.ignore = true;
  e.add_frame({box(0, 1, kA), box(0, 2, kB)}, {box(0, 1, kA), ignored});
  const TrackingScores s = e.scores();
  EXPECT_EQ(s.ground_truth, 1);
  EXPECT_EQ(s.hypotheses, 1);
  EXPECT_EQ(s.fp, 0);
  EXPECT_DOUBLE_EQ(s.mota, 1.0);
}

TEST(TrackingEvaluator, DuplicateTrackIdIsAnError) {
  TrackingEvaluator e;
  EXPECT_THROW(e.add_frame({box(4, 1, kA), box(4, 1, kB)}, {}), ProcessingError);
}

TEST(TrackingEvaluator, NoGroundTruthGivesZeroNotNan) {
  TrackingEvaluator e;
  e.add_frame({}, {});
  const TrackingScores s = e.scores();
  EXPECT_EQ(s.mota, 0.0);
  EXPECT_EQ(s.idf1, 0.0);
  EXPECT_EQ(s.frames, 1);
}

}  // namespace
}  // namespace bodyrec
