#include "bodyrec/tracking/floor_tracker.h"

#include <set>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Two people pass each other: A walks right at 2.2 m from the camera, B walks left at 2.8 m, 5 cm per
// frame each (1.5 m/s); their image boxes overlap around frame 30, their footprints never do. B is hidden
// behind A (no detection) on frames 27-33.
cv::Vec2d a_at(int f) { return {-1.5 + 0.05 * f, 2.2}; }
cv::Vec2d b_at(int f) { return {1.5 - 0.05 * f, 2.8}; }
bool b_hidden(int f) { return f >= 27 && f <= 33; }

TEST(FloorTracker, PeoplePassingInFrontOfEachOtherKeepTheirIds) {
  FloorTracker tracker;  // min_hits 3
  int id_a = -1, id_b = -1;
  for (int f = 0; f < 60; ++f) {
    std::vector<cv::Vec2d> where = {a_at(f)};
    if (!b_hidden(f)) where.push_back(b_at(f));
    const std::vector<int> ids = tracker.update(f, where);
    ASSERT_EQ(ids.size(), where.size());
    if (f < 2) {  // not seen for 3 frames yet
      EXPECT_EQ(ids[0], -1) << "frame " << f;
      continue;
    }
    if (f == 2) id_a = ids[0], id_b = ids[1];
    EXPECT_EQ(ids[0], id_a) << "frame " << f;
    if (!b_hidden(f)) {
      EXPECT_EQ(ids[1], id_b) << "frame " << f;
    }
  }
  EXPECT_GE(id_a, 1);
  EXPECT_GE(id_b, 1);
  EXPECT_NE(id_a, id_b);
}

TEST(FloorTracker, SomeoneGoneLongerThanMaxAgeIsNewAndFlickersGetNoId) {
  FloorTrackerOptions o;
  o.max_age = 10;
  FloorTracker tracker(o);
  int first = -1;
  for (int f = 0; f < 5; ++f) first = tracker.update(f, {{0.0, 3.0}})[0];
  ASSERT_GE(first, 1);
  // A fragment that shows for one frame next to nobody: no id.
  EXPECT_EQ(tracker.update(5, {{0.0, 3.0}, {2.0, 4.0}})[1], -1);
  // Gone for 20 frames (> max_age), back at the same place: a new person.
  int again = -1;
  for (int f = 26; f < 30; ++f) again = tracker.update(f, {{0.0, 3.0}})[0];
  EXPECT_GE(again, 1);
  EXPECT_NE(again, first);
}

TEST(FloorTracker, SomeoneWhoWalkedOutAtTheSideIsNotTheNextOneComingIn) {
  FloorTracker tracker;  // walk_out_frames 2
  // A walks right and out of view: touches the image's side on frames 8-9, then is gone.
  int a = -1;
  for (int f = 0; f < 10; ++f) a = tracker.update(f, {{1.0 + 0.05 * f, 3.0}}, {f >= 8})[0];
  ASSERT_GE(a, 1);
  // B comes in at the same side 0.1 s later, right where A's track is predicted: a new id.
  int b = -1;
  for (int f = 13; f < 20; ++f) b = tracker.update(f, {{1.45 - 0.05 * (f - 13), 3.0}}, {f < 15})[0];
  EXPECT_GE(b, 1);
  EXPECT_NE(b, a);
  // Without the rule (walk_out_frames 0) the box tracker hands A's track to B.
  FloorTrackerOptions keep;
  keep.walk_out_frames = 0;
  FloorTracker plain(keep);
  int a0 = -1, b0 = -1;
  for (int f = 0; f < 10; ++f) a0 = plain.update(f, {{1.0 + 0.05 * f, 3.0}}, {f >= 8})[0];
  for (int f = 13; f < 20; ++f) b0 = plain.update(f, {{1.45 - 0.05 * (f - 13), 3.0}}, {f < 15})[0];
  EXPECT_EQ(b0, a0);
  // C at the side whose segment drops out for one frame only keeps its id.
  FloorTracker other;
  int c = -1;
  for (int f = 0; f < 6; ++f) c = other.update(f, {{1.5, 3.0}}, {true})[0];
  EXPECT_EQ(other.update(7, {{1.5, 3.0}}, {true})[0], c);
  // ... and a person away from the side, hidden for longer, keeps theirs (PeoplePassing... above).
  EXPECT_THROW(other.update(8, {{1.5, 3.0}}, {true, false}), UsageError);
}

TEST(FloorTracker, OptionsAreChecked) {
  FloorTrackerOptions o;
  o.footprint_m = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.min_hits = 0;
  EXPECT_THROW(FloorTracker{o}, UsageError);
}

}  // namespace
}  // namespace bodyrec
