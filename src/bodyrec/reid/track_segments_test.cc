#include "bodyrec/reid/track_segments.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// A whole-body scan (60x180, every pixel body) with a shirt over trousers.
PartialScan scan(const cv::Scalar& shirt, const cv::Scalar& trousers, double quality = 0.8) {
  PartialScan s;
  s.image = cv::Mat(180, 60, CV_8UC3, trousers);
  s.image(cv::Rect(0, 0, 60, 90)).setTo(shirt);
  s.mask = cv::Mat(180, 60, CV_8U, cv::Scalar(255));
  s.quality = quality;
  return s;
}

const cv::Scalar kRed(40, 40, 200), kBlue(200, 60, 30), kGreen(40, 180, 40), kYellow(40, 220, 230);

TEST(TrackSegments, KeepsTheTrackIdWhileTheAppearanceStays) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue);
  for (int i = 0; i < 10; ++i) {
    s.next_frame();
    EXPECT_EQ(s.key(7, &a), 7u);
    EXPECT_EQ(s.key(8, nullptr), 8u);
  }
  EXPECT_EQ(s.cuts(), 0);
}

TEST(TrackSegments, CutsAfterTwoClearMissesInARow) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue), b = scan(kGreen, kYellow);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(s.key(7, &a), 7u);
  EXPECT_EQ(s.key(7, &b), 7u);  // one strike
  EXPECT_EQ(s.key(7, &b), 7u + (1ull << 32));
  EXPECT_EQ(s.cuts(), 1);
  // The new segment learned from the scan that cut it: b stays, a cuts again.
  EXPECT_EQ(s.key(7, &b), 7u + (1ull << 32));
  EXPECT_EQ(s.key(7, &a), 7u + (1ull << 32));
  EXPECT_EQ(s.key(7, &a), 7u + (2ull << 32));
  EXPECT_EQ(s.key(7, nullptr), 7u + (2ull << 32));
}

TEST(TrackSegments, AMatchBetweenMissesResetsTheStrikes) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue), b = scan(kGreen, kYellow);
  s.key(3, &a);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(s.key(3, &b), 3u);
    EXPECT_EQ(s.key(3, &a), 3u);
  }
  EXPECT_EQ(s.cuts(), 0);
}

TEST(TrackSegments, PoorScansNeitherStrikeNorTeach) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue), poor = scan(kGreen, kYellow, 0.3);
  s.key(3, &a);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.key(3, &poor), 3u);
  EXPECT_EQ(s.cuts(), 0);
}

TEST(TrackSegments, DisabledKeepsTheTrackId) {
  const auto matcher = make_matcher("stripes");
  TrackSegmentOptions o;
  o.enabled = false;
  TrackSegments s(*matcher, o);
  const PartialScan a = scan(kRed, kBlue), b = scan(kGreen, kYellow);
  s.key(3, &a);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.key(3, &b), 3u);
}

TEST(TrackSegments, ForgetsTracksUnseenForLong) {
  const auto matcher = make_matcher("stripes");
  TrackSegmentOptions o;
  o.forget_after = 2;
  TrackSegments s(*matcher, o);
  const PartialScan a = scan(kRed, kBlue), b = scan(kGreen, kYellow);
  s.key(3, &a);
  s.key(3, &b);  // one strike
  for (int i = 0; i < 3; ++i) s.next_frame();
  // Forgotten: no references, no strike; b is learned afresh.
  EXPECT_EQ(s.key(3, &b), 3u);
  EXPECT_EQ(s.key(3, &b), 3u);
  EXPECT_EQ(s.cuts(), 0);
}

TEST(TrackSegments, ANewTrackIdContinuesAPersonLostAMomentAgo) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue), b = scan(kGreen, kYellow);
  s.next_frame();
  s.key(3, &a);
  s.key(4, &b);
  for (int i = 0; i < 5; ++i) s.next_frame();  // 3 and 4 lost
  EXPECT_EQ(s.key(9, nullptr), 9u);  // no clear scan yet: its own key
  EXPECT_EQ(s.key(9, &a), 3u);       // the first clear one is 3's
  EXPECT_EQ(s.joins(), 1);
  EXPECT_EQ(s.key(9, &a), 3u);
  // Tracker id 3 showing again is someone else now.
  EXPECT_EQ(s.key(3, &a), 3u + (1ull << 32));
  // A new id like b continues 4.
  EXPECT_EQ(s.key(10, &b), 4u);
}

TEST(TrackSegments, NoJoinWhileTheOldTrackIsInViewOrLongGone) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue);
  s.next_frame();
  s.key(3, &a);
  s.next_frame();
  s.key(3, &a);
  EXPECT_EQ(s.key(9, &a), 9u);  // 3 is in view: two people dressed alike
  for (int i = 0; i < 40; ++i) s.next_frame();
  EXPECT_EQ(s.key(11, &a), 11u);  // 3 and 9 lost too long ago (join_within 30)
  EXPECT_EQ(s.joins(), 0);
}

TEST(TrackSegments, NoJoinWhenTwoLostPeopleLookAlike) {
  const auto matcher = make_matcher("stripes");
  TrackSegments s(*matcher);
  const PartialScan a = scan(kRed, kBlue);
  s.next_frame();
  s.key(3, &a);
  s.key(4, &a);
  for (int i = 0; i < 3; ++i) s.next_frame();
  EXPECT_EQ(s.key(9, &a), 9u);
  EXPECT_EQ(s.joins(), 0);
}

TEST(TrackSegments, BadOptionsAreUsageErrors) {
  const auto matcher = make_matcher("stripes");
  TrackSegmentOptions o;
  o.strikes = 0;
  EXPECT_THROW(TrackSegments(*matcher, o), UsageError);
  o = {};
  o.min_quality = 1.5;
  EXPECT_THROW(TrackSegments(*matcher, o), UsageError);
  o = {};
  o.cut_gap = -1;
  EXPECT_THROW(TrackSegments(*matcher, o), UsageError);
  o = {};
  o.references = 0;
  EXPECT_THROW(TrackSegments(*matcher, o), UsageError);
  o = {};
  o.join_within = -1;
  EXPECT_THROW(TrackSegments(*matcher, o), UsageError);
}

}  // namespace
}  // namespace bodyrec
