#include "bodyrec/tracking/detect_and_track.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// A scripted detector: one person walking right 4 px per frame plus, on full detections only, a still
// "clutter" box; it records which kind of search each frame got and where it was asked to look.
class ScriptedDetector : public PeopleDetector {
 public:
  std::vector<Detection> detect(const cv::Mat&) override {
    calls.push_back('F');
    std::vector<Detection> out{{person(), 1.0}};
    if (clutter_until > frame) out.push_back({Box(400, 50, 30, 80), 1.0});
    ++frame;
    return out;
  }
  std::vector<Detection> detect_near(const cv::Mat&, const std::vector<Box>& expected) override {
    calls.push_back('L');
    asked.push_back(expected);
    std::vector<Detection> out;
    for (const Box& b : expected)  // finds whatever is near an expected box, clutter included
      if (iou(b, person()) > 0.3) out.push_back({person(), 1.0});
      else out.push_back({b, 1.0});
    out.push_back({Box(200, 200, 30, 80), 1.0});  // a newcomer: local searches must not start tracks
    ++frame;
    return out;
  }
  std::string describe() const override { return "scripted"; }
  Box person() const { return Box(10 + 4.0 * frame, 50, 30, 80); }

  int frame = 0, clutter_until = 1000;
  std::string calls;
  std::vector<std::vector<Box>> asked;
};

TEST(DetectAndTrack, AlternatesFullAndLocalSearchesAndNeverStartsTracksLocally) {
  ScriptedDetector detector;
  DetectAndTrackOptions o;
  o.tracker.min_hits = 1;
  DetectAndTrack tracking(detector, o);
  std::vector<TrackedPerson> last;
  for (int i = 0; i < 6; ++i) {
    last = tracking.step(i, cv::Mat());
    EXPECT_EQ(tracking.last_was_full(), i % 2 == 0) << i;
  }
  EXPECT_EQ(detector.calls, "FLFLFL");
  ASSERT_EQ(last.size(), 2u);  // the person and the clutter, never the local-only newcomer
  EXPECT_EQ(last[0].id, 1);
  EXPECT_NEAR(last[0].box.x, 10 + 4.0 * 5, 2.0);
  EXPECT_EQ(detector.asked.front().size(), 2u);
}

TEST(DetectAndTrack, LocalSearchesDoNotKeepAlivePeopleTheFullDetectorLost) {
  ScriptedDetector detector;
  detector.clutter_until = 3;  // the full detector stops reporting the still box after frame 2
  DetectAndTrackOptions o;
  o.tracker.min_hits = 1;
  o.tracker.coast_frames = 0;
  DetectAndTrack tracking(detector, o);
  std::vector<TrackedPerson> last;
  for (int i = 0; i < 12; ++i) last = tracking.step(i, cv::Mat());
  // Frame 4 (full) misses the clutter, so frame 5's local search is not asked about it.
  ASSERT_GE(detector.asked.size(), 3u);
  EXPECT_EQ(detector.asked[1].size(), 2u);  // frame 3: clutter still matched on frame 2
  EXPECT_EQ(detector.asked[2].size(), 1u);  // frame 5
  ASSERT_EQ(last.size(), 1u);
  EXPECT_EQ(last[0].id, 1);
}

TEST(DetectAndTrack, PredictModeNeverSearchesAndBadOptionsAreUsageErrors) {
  ScriptedDetector detector;
  DetectAndTrackOptions o;
  o.detect_every = 3;
  o.between = BetweenDetections::kPredict;
  DetectAndTrack tracking(detector, o);
  for (int i = 0; i < 7; ++i) tracking.step(i, cv::Mat());
  EXPECT_EQ(detector.calls, "FFF");
  o.detect_every = 0;
  EXPECT_THROW(DetectAndTrack(detector, o), UsageError);
  EXPECT_FALSE(parse_between_detections("nearby"));
  EXPECT_EQ(parse_between_detections("predict"), BetweenDetections::kPredict);
  EXPECT_STREQ(to_string(BetweenDetections::kLocal), "local");
}

}  // namespace
}  // namespace bodyrec
