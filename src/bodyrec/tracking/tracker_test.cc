#include "bodyrec/tracking/tracker.h"

#include <algorithm>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Two people 40x100 px crossing: A walks right from x=50, B walks left from x=250, 4 px per frame each,
// B 10 px lower; they overlap most around frame 25. A's detection is missing on frames 23-25, right in
// the crossing, so the tracker must not hand B's detection to A.
Box person_a(int f) { return Box(50 + 4.0 * f, 100, 40, 100); }
Box person_b(int f) { return Box(250 - 4.0 * f, 110, 40, 100); }
bool a_missed(int f) { return f >= 23 && f <= 25; }

std::vector<Detection> detections_at(int f) {
  std::vector<Detection> d;
  if (!a_missed(f)) d.push_back({person_a(f), 1.0});
  d.push_back({person_b(f), 1.0});
  return d;
}

int count_state(const std::vector<TrackedPerson>& tracks, TrackState state) {
  int n = 0;
  for (const auto& t : tracks) n += t.state == state;
  return n;
}

TEST(MultiTracker, CrossingPeopleKeepTheirIdsThroughAMissedDetection) {
  TrackerOptions o;
  o.coast_frames = 5;  // report A through its 3 missed frames (as lost)
  MultiTracker tracker(o);  // min_hits 3 by default
  std::map<int, int> id_of;  // person (0 = A, 1 = B) -> track id
  for (int f = 0; f < 60; ++f) {
    const auto tracks = tracker.update(f, detections_at(f));
    if (f < 2) {  // confirmation needs 3 hits: frames 0, 1, 2
      EXPECT_TRUE(tracks.empty()) << "frame " << f;
      continue;
    }
    ASSERT_EQ(tracks.size(), 2u) << "frame " << f;
    EXPECT_EQ(count_state(tracks, TrackState::kConfirmed), a_missed(f) ? 1 : 2) << "frame " << f;
    EXPECT_EQ(count_state(tracks, TrackState::kLost), a_missed(f) ? 1 : 0) << "frame " << f;
    for (const auto& t : tracks) {
      // Which person is this box? The closer truth box.
      const int person = iou(t.box, person_a(f)) >= iou(t.box, person_b(f)) ? 0 : 1;
      if (!a_missed(f) || f < 22) {
        const auto [it, inserted] = id_of.emplace(person, t.id);
        EXPECT_EQ(it->second, t.id) << "frame " << f << " person " << person;
      }
      EXPECT_GT(std::max(iou(t.box, person_a(f)), iou(t.box, person_b(f))), 0.7) << "frame " << f;
    }
  }
  EXPECT_EQ(id_of.size(), 2u);
  EXPECT_EQ(id_of[0], 1);
  EXPECT_EQ(id_of[1], 2);
}

TEST(MultiTracker, PredictsBetweenSparseDetections) {
  TrackerOptions o;
  o.coast_frames = 5;  // A's detection on frame 24 is missing: reported as lost until frame 27
  MultiTracker tracker(o);
  std::set<int> ids;
  for (int f = 0; f < 60; ++f) {
    // Detection on every 3rd frame only; A's detection also missing on frame 24 (within 23-25).
    const auto tracks = f % 3 == 0 ? tracker.update(f, detections_at(f)) : tracker.predict_only(f);
    for (const auto& t : tracks) ids.insert(t.id);
    if (f >= 6) {  // confirmed at the 3rd detection, frame 6
      ASSERT_EQ(tracks.size(), 2u) << "frame " << f;
      for (const auto& t : tracks)
        EXPECT_GT(std::max(iou(t.box, person_a(f)), iou(t.box, person_b(f))), 0.6) << "frame " << f;
    } else {
      EXPECT_TRUE(tracks.empty()) << "frame " << f;
    }
  }
  EXPECT_EQ(ids, (std::set<int>{1, 2}));
}

TEST(MultiTracker, SingleFalseAlarmsAreNeverConfirmed) {
  MultiTracker tracker;
  for (int f = 0; f < 20; ++f) {
    std::vector<Detection> d = {{person_a(f), 1.0}};
    if (f % 2 == 0) d.push_back({Box(400 + 30.0 * f, 20, 30, 70), 0.5});  // never twice in one place
    const auto tracks = tracker.update(f, d);
    if (f >= 2) {
      EXPECT_EQ(tracks.size(), 1u) << "frame " << f;
    }
  }
}

TEST(MultiTracker, EachTrackSaysWhichDetectionItGot) {
  MultiTracker tracker;
  for (int f = 0; f < 10; ++f) {
    // A weak box first (below min_score 0.3: ignored), then B, then A: indices into this very list.
    const std::vector<Detection> d = {{Box(600, 20, 30, 70), 0.1}, {person_b(f), 1.0}, {person_a(f), 1.0}};
    for (const TrackedPerson& t : tracker.all_tracks()) EXPECT_NE(t.detection, 0);
    const auto tracks = tracker.update(f, d);
    for (const TrackedPerson& t : tracker.all_tracks()) {
      ASSERT_GE(t.detection, 1) << "frame " << f;
      EXPECT_GT(iou(t.box, d[static_cast<size_t>(t.detection)].box), 0.7) << "frame " << f;
    }
    if (f >= 2) {
      ASSERT_EQ(tracks.size(), 2u);
    }
  }
  for (const TrackedPerson& t : tracker.predict_only(10)) EXPECT_EQ(t.detection, -1);
}

TEST(MultiTracker, LostTracksAreReportedForCoastFramesAndDeletedAfterMaxAge) {
  TrackerOptions o;
  o.max_age = 10;
  o.coast_frames = 2;
  MultiTracker tracker(o);
  for (int f = 0; f < 5; ++f) tracker.update(f, {{person_a(f), 1.0}});
  // Person A leaves after frame 4: reported as lost on frames 5 and 6 (1 and 2 frames after the last
  // match), then no more; kept internally while frames since the match <= 10, i.e. up to frame 14.
  for (int f = 5; f <= 14; ++f) {
    const auto tracks = tracker.update(f, {});
    EXPECT_EQ(tracks.size(), f <= 6 ? 1u : 0u) << "frame " << f;
    EXPECT_EQ(tracker.all_tracks().size(), 1u) << "frame " << f;
  }
  EXPECT_TRUE(tracker.update(15, {}).empty());
  EXPECT_TRUE(tracker.all_tracks().empty());
}

TEST(MultiTracker, ReassociatesAfterOcclusionByDistance) {
  MultiTracker tracker;
  for (int f = 0; f < 10; ++f) tracker.update(f, {{person_a(f), 1.0}});
  // Hidden for 8 frames; reappears a bit off its predicted path (shifted 15 px: low IoU with the
  // prediction but close by centre distance). Same id.
  for (int f = 10; f < 18; ++f) tracker.update(f, {});
  const Box back(person_a(18).x + 15, person_a(18).y + 5, 40, 100);
  const auto tracks = tracker.update(18, {{back, 1.0}});
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].id, 1);
  EXPECT_EQ(tracks[0].state, TrackState::kConfirmed);
}

// Bad-input table (docs/reliability.md): 500 detections in a frame, then frames with none. A 25x20 grid of
// 30x60 boxes 40 px apart (no two overlap), moving 2 px right per frame: every box keeps its own track.
TEST(MultiTracker, FiveHundredDetectionsThenNoneKeepOneTrackPerPerson) {
  const auto crowd = [](int f) {
    std::vector<Detection> d;
    for (int row = 0; row < 20; ++row)
      for (int col = 0; col < 25; ++col) d.push_back({Box(col * 40.0 + 2.0 * f, row * 70.0, 30, 60), 1.0});
    return d;
  };
  MultiTracker tracker;  // min_hits 3, coast_frames 1
  EXPECT_TRUE(tracker.update(0, crowd(0)).empty());
  EXPECT_EQ(tracker.all_tracks().size(), 500u);
  tracker.update(1, crowd(1));
  const auto tracks = tracker.update(2, crowd(2));
  ASSERT_EQ(tracks.size(), 500u);
  const auto truth = crowd(2);
  for (size_t i = 0; i < tracks.size(); ++i) {
    EXPECT_EQ(tracks[i].id, static_cast<int>(i) + 1);  // ids 1..500, sorted
    EXPECT_EQ(tracks[i].state, TrackState::kConfirmed);
    double best = 0;
    for (const auto& d : truth) best = std::max(best, iou(tracks[i].box, d.box));
    EXPECT_GT(best, 0.9) << "track " << tracks[i].id;
  }
  // No detections: all 500 coast one frame as lost, then are no longer reported.
  const auto lost = tracker.update(3, {});
  ASSERT_EQ(lost.size(), 500u);
  EXPECT_EQ(count_state(lost, TrackState::kLost), 500);
  EXPECT_TRUE(tracker.update(4, {}).empty());
  EXPECT_EQ(tracker.all_tracks().size(), 500u);  // kept for max_age frames
  // Back: the same ids, no new ones.
  tracker.update(5, crowd(5));
  const auto back = tracker.update(6, crowd(6));
  ASSERT_EQ(back.size(), 500u);
  EXPECT_EQ(back.front().id, 1);
  EXPECT_EQ(back.back().id, 500);
}

TEST(MultiTracker, RejectsFramesGoingBackwardsAndBadOptions) {
  MultiTracker tracker;
  tracker.update(5, {});
  EXPECT_THROW(tracker.update(5, {}), ProcessingError);
  EXPECT_THROW(tracker.predict_only(3), ProcessingError);
  TrackerOptions o;
  o.iou_gate = 0;
  EXPECT_THROW(MultiTracker{o}, UsageError);
  o = TrackerOptions();
  o.min_hits = 0;
  EXPECT_THROW(o.check(), UsageError);
}

}  // namespace
}  // namespace bodyrec

namespace bodyrec {
namespace {

// Library checks name the options struct and field, so that any front end can map them to its own names.
TEST(TrackerOptions, ABadValueNamesTheStructAndTheField) {
  TrackerOptions options;
  options.min_hits = 0;
  try {
    options.check();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.options(), "TrackerOptions");
    EXPECT_EQ(e.field(), "min_hits");
    EXPECT_EQ(e.problem(), "must be >= 1");
    EXPECT_STREQ(e.what(), "TrackerOptions.min_hits must be >= 1");
    EXPECT_EQ(e.code(), ExitCode::kUsage);
  }
}

}  // namespace
}  // namespace bodyrec
