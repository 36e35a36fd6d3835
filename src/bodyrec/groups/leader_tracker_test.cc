#include "bodyrec/groups/leader_tracker.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace bodyrec {
namespace {

// A 320x240 noisy-grey scene; a textured "person" (checker pattern) at `box` when visible.
cv::Mat scene(const std::optional<Box>& box, int seed) {
  cv::Mat img(240, 320, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::NORMAL, 110, 6);
  if (box) {
    const cv::Rect r(*box);
    for (int y = r.y; y < r.y + r.height; ++y)
      for (int x = r.x; x < r.x + r.width; ++x)
        img.at<uchar>(y, x) = static_cast<uchar>(((x - r.x) / 6 + (y - r.y) / 6) % 2 ? 230 : 20);
  }
  return img;
}

// The same scene with a person of 6 px blocks of fixed random dark or light grey: a regular checker board
// has a correlation peak every period, and which of them wins then depends on floating-point rounding
// (it changed with the BLAS library), so tests of the tracked position use this one.
cv::Mat random_block_scene(const Box& box, int seed) {
  cv::Mat img = scene(std::nullopt, seed);
  const cv::Rect r(box);
  cv::RNG texture(7);
  cv::Mat blocks(r.height / 6 + 1, r.width / 6 + 1, CV_8UC1);
  for (int i = 0; i < blocks.rows; ++i)
    for (int j = 0; j < blocks.cols; ++j) blocks.at<uchar>(i, j) = texture.uniform(0, 2) ? 230 : 20;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) img.at<uchar>(y, x) = blocks.at<uchar>((y - r.y) / 6, (x - r.x) / 6);
  return img;
}

TrackedPerson track(int id, const Box& box, int since_match = 0) {
  TrackedPerson t;
  t.id = id;
  t.box = box;
  t.state = since_match ? TrackState::kLost : TrackState::kConfirmed;
  t.frames_since_match = since_match;
  return t;
}

TEST(LeaderTracker, FollowsTheLeaderThroughDetectorMisses) {
  LeaderTracker leader;
  Box box(50, 60, 36, 90);
  auto s = leader.update(random_block_scene(box, 0), {track(3, box)}, 3);
  EXPECT_EQ(s.state, LeaderState::kTracking);
  EXPECT_EQ(s.track_id, 3);
  // Five frames of walking right with no detection (the track coasts on its prediction, off by 10 px).
  for (int f = 1; f <= 5; ++f) {
    box.x += 4;
    s = leader.update(random_block_scene(box, f), {track(3, Box(box.x - 10, box.y, 36, 90), f)}, 3);
    ASSERT_EQ(s.state, LeaderState::kTracking) << f;
    EXPECT_GT(s.psr, 6.0);
    EXPECT_NEAR(s.box.x, box.x, 3.0) << f;  // the DSST box, not the coasting prediction
  }
}

TEST(LeaderTracker, LostWhenNoDetectionSupportsItThenReacquiredFromItsTrack) {
  LeaderTrackerOptions o;
  o.max_unsupported = 4;
  LeaderTracker leader(o);
  const Box box(50, 60, 36, 90);
  leader.update(scene(box, 0), {track(3, box)}, 3);
  // The person is gone (occluded, out of view) and nothing is detected there; the static background
  // keeps a sharp correlation peak, but 4 frames without support mean lost.
  LeaderStatus s;
  for (int f = 1; f <= 3; ++f) {
    s = leader.update(scene(std::nullopt, 0), {}, 3);
    EXPECT_EQ(s.state, LeaderState::kTracking) << f;
  }
  s = leader.update(scene(std::nullopt, 0), {}, 3);
  ASSERT_EQ(s.state, LeaderState::kLost);
  EXPECT_EQ(s.lost_reason, "unsupported");
  EXPECT_TRUE(s.box.empty());
  s = leader.update(scene(std::nullopt, 0), {}, 3);
  EXPECT_EQ(s.state, LeaderState::kLost);
  EXPECT_TRUE(s.lost_reason.empty());  // reported once, on the frame of the loss
  // The leader's own track is detected again elsewhere: re-acquired there.
  const Box back(200, 80, 36, 90);
  s = leader.update(scene(back, 0), {track(3, back)}, 3);
  EXPECT_EQ(s.state, LeaderState::kTracking);
  EXPECT_TRUE(s.reacquired);
  EXPECT_EQ(s.track_id, 3);
  EXPECT_EQ(s.box, back);
}

TEST(LeaderTracker, WeakPeakMeansLost) {
  LeaderTrackerOptions o;
  o.min_psr = 20;  // above what this tracker reaches on a changing scene
  LeaderTracker leader(o);
  const Box box(50, 60, 36, 90);
  leader.update(scene(box, 0), {track(3, box)}, 3);
  const auto s = leader.update(scene(box, 1), {track(3, box)}, 3);
  EXPECT_EQ(s.state, LeaderState::kLost);
  EXPECT_EQ(s.lost_reason, "weak peak");
}

TEST(LeaderTracker, HandsTheRoleToTheTrackThatReplacesAnEndedOne) {
  LeaderTracker leader;
  Box box(50, 60, 36, 90);
  leader.update(scene(box, 0), {track(3, box), track(4, Box(250, 60, 36, 90))}, 3);
  // Track 3 ends (the tracker lost it) while the person walks on; a new track 9 starts on the person.
  box.x += 3;
  auto s = leader.update(scene(box, 1), {track(4, Box(250, 60, 36, 90))}, 3);
  EXPECT_EQ(s.state, LeaderState::kTracking);
  EXPECT_EQ(s.track_id, 3);
  box.x += 3;
  s = leader.update(scene(box, 2), {track(4, Box(250, 60, 36, 90)), track(9, box)}, 3);
  EXPECT_EQ(s.track_id, 9);
  ASSERT_TRUE(s.handed_over_from.has_value());
  EXPECT_EQ(*s.handed_over_from, 3);
  EXPECT_TRUE(s.reacquired);
}

TEST(LeaderTracker, DisagreementWithDetectionsMeansLost) {
  LeaderTrackerOptions o;
  o.max_disagreement = 2;
  LeaderTracker leader(o);
  const Box box(50, 60, 36, 90);
  leader.update(scene(box, 0), {track(3, box)}, 3);
  // The person stays where it is, but the detector puts the leader's track far away (an id swap).
  auto s = leader.update(scene(box, 1), {track(3, Box(220, 60, 36, 90))}, 3);
  EXPECT_EQ(s.state, LeaderState::kTracking);
  s = leader.update(scene(box, 2), {track(3, Box(222, 60, 36, 90))}, 3);
  EXPECT_EQ(s.state, LeaderState::kLost);
  EXPECT_EQ(s.lost_reason, "disagrees");
}

TEST(LeaderTracker, NoLeaderNoTracking) {
  LeaderTracker leader;
  const auto s = leader.update(scene(std::nullopt, 0), {}, std::nullopt);
  EXPECT_EQ(s.state, LeaderState::kNone);
  EXPECT_EQ(to_string(s.state), "none");
}

}  // namespace
}  // namespace bodyrec
