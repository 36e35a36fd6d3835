#include "bodyrec/reid/online_reid.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// A person seen in one view: shirt and trousers of their colours, a little noise per frame.
PartialScan scan_of(const cv::Scalar& shirt, const cv::Scalar& trousers, View view, int frame, double quality = 0.8) {
  PartialScan s;
  s.image = cv::Mat(200, 80, CV_8UC3, cv::Scalar(0, 0, 0));
  s.mask = cv::Mat(200, 80, CV_8U, cv::Scalar(0));
  cv::circle(s.image, {40, 18}, 14, cv::Scalar(90, 120, 170), cv::FILLED);
  cv::rectangle(s.image, cv::Rect(15, 34, 50, 70), shirt, cv::FILLED);
  cv::rectangle(s.image, cv::Rect(20, 104, 40, 92), trousers, cv::FILLED);
  cv::Mat grey;
  cv::cvtColor(s.image, grey, cv::COLOR_BGR2GRAY);
  s.mask = grey > 0;
  cv::Mat noise(s.image.size(), CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(frame + 1));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
  cv::add(s.image, noise, s.image, s.mask);
  s.box = cv::Rect(100, 50, 80, 200);
  s.pixels = cv::countNonZero(s.mask);
  s.completeness = s.sharpness = s.resolution = 1;
  s.quality = quality;
  s.view.view = view;
  s.view.confidence = 0.9;
  return s;
}

const cv::Scalar kRed(30, 30, 210), kBlue(160, 60, 20), kGreen(40, 180, 40), kYellow(30, 210, 220);

ReidBody body(uint64_t track, const cv::Scalar& shirt, const cv::Scalar& trousers, View view, int frame,
              double quality = 0.8) {
  ReidBody b;
  b.track = track;
  b.view.view = view;
  b.view.confidence = 0.9;
  b.scan = scan_of(shirt, trousers, view, frame, quality);
  b.box = b.scan->box;
  return b;
}

struct Fixture {
  testing::TempDir dir;
  std::unique_ptr<Gallery> gallery;
  std::unique_ptr<AppearanceMatcher> matcher = make_matcher("stripes");
  std::unique_ptr<OnlineReid> reid;
  int frame = 0;
  explicit Fixture(OnlineReidOptions o = {}) {
    GalleryOptions g;
    g.create = true;
    g.sync_full = false;
    gallery = std::make_unique<Gallery>((dir.path() / "g.db").string(), g);
    reid = std::make_unique<OnlineReid>(*gallery, *matcher, o);
  }
  ReidStep step(const std::vector<ReidBody>& bodies) {
    const ReidStep s = reid->step(frame / 30.0, bodies);
    ++frame;
    return s;
  }
};

int count(const std::vector<ReidEvent>& events, ReidEventKind kind) {
  int n = 0;
  for (const ReidEvent& e : events) n += e.kind == kind;
  return n;
}

TEST(OnlineReid, EnrolsAfterEnoughScansNotFromOneFrame) {
  Fixture f;
  for (int i = 0; i < 3; ++i) {
    const ReidStep s = f.step({body(7, kRed, kBlue, View::F, i)});
    ASSERT_EQ(s.identities.size(), 1u);
    EXPECT_FALSE(s.identities[0].user) << "frame " << i;
    EXPECT_TRUE(s.events.empty());
  }
  const ReidStep s = f.step({body(7, kRed, kBlue, View::F, 3)});
  ASSERT_TRUE(s.identities[0].user);
  EXPECT_EQ(*s.identities[0].user, 1);
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_EQ(s.events[0].kind, ReidEventKind::kEnrolled);
  EXPECT_EQ(s.events[0].track, 7u);
  EXPECT_EQ(s.events[0].view, View::F);
  EXPECT_EQ(f.gallery->user_count(), 1);
  EXPECT_EQ(f.gallery->user_scans(1).size(), 1u);
}

TEST(OnlineReid, LeavesAndComesBackUnderANewTrackAsTheSameUser) {
  Fixture f;
  for (int i = 0; i < 6; ++i) f.step({body(7, kRed, kBlue, View::F, i)});
  // Gone for a second: `left` once the track has been unseen for left_after_s (0.5 s).
  std::vector<ReidEvent> events;
  for (int i = 0; i < 30; ++i)
    for (const ReidEvent& e : f.step({}).events) events.push_back(e);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, ReidEventKind::kLeft);
  EXPECT_EQ(events[0].user, 1);
  EXPECT_EQ(f.reid->live_tracks(), 0u);
  // Back, seen from behind this time, with another tracking id.
  std::optional<ReidEvent> recognised;
  std::optional<UserId> user;
  for (int i = 0; i < 5; ++i) {
    const ReidStep s = f.step({body(9, kRed, kBlue, View::B, 100 + i)});
    for (const ReidEvent& e : s.events)
      if (e.kind == ReidEventKind::kRecognised) recognised = e;
    user = s.identities[0].user;
  }
  ASSERT_TRUE(recognised);
  EXPECT_EQ(recognised->user, 1);
  EXPECT_EQ(recognised->track, 9u);
  ASSERT_TRUE(recognised->score);
  EXPECT_GT(*recognised->score, f.reid->threshold());
  EXPECT_EQ(user, 1);
  EXPECT_EQ(f.gallery->user_count(), 1);
  // The back view it lacked was added.
  EXPECT_EQ(f.gallery->user_scans(1).size(), 2u);
}

TEST(OnlineReid, TwoPeopleAtOnceAreTwoUsers) {
  Fixture f;
  std::optional<UserId> a, b;
  for (int i = 0; i < 5; ++i) {
    const ReidStep s = f.step({body(1, kRed, kBlue, View::F, i), body(2, kGreen, kYellow, View::SR, i + 50)});
    a = s.identities[0].user;
    b = s.identities[1].user;
  }
  ASSERT_TRUE(a && b);
  EXPECT_NE(*a, *b);
  EXPECT_EQ(f.gallery->user_count(), 2);
}

TEST(OnlineReid, LookalikesInOneFrameAreNeverMerged) {
  Fixture f;
  for (int i = 0; i < 5; ++i) f.step({body(1, kRed, kBlue, View::F, i)});
  // Someone dressed the same way walks in while the first is still there.
  std::optional<UserId> twin;
  for (int i = 0; i < 40; ++i) twin = f.step({body(1, kRed, kBlue, View::F, 10 + i), body(2, kRed, kBlue, View::F, 60 + i)}).identities[1].user;
  ASSERT_TRUE(twin);
  EXPECT_NE(*twin, 1);
  EXPECT_EQ(f.gallery->user_count(), 2);
}

TEST(OnlineReid, PoorScansAreNotEvidence) {
  Fixture f;
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(f.step({body(3, kRed, kBlue, View::F, i, 0.1)}).identities[0].user);
  EXPECT_EQ(f.gallery->user_count(), 0);
  ReidBody no_view = body(3, kRed, kBlue, View::F, 11);
  no_view.view.view.reset();
  EXPECT_FALSE(f.reid->wants_scan(3, no_view.view));
  EXPECT_TRUE(f.reid->wants_scan(3, body(3, kRed, kBlue, View::F, 12).view));
}

TEST(OnlineReid, AssignedTracksAddMissingViewsOnce) {
  Fixture f;
  for (int i = 0; i < 4; ++i) f.step({body(5, kRed, kBlue, View::F, i)});
  ASSERT_EQ(f.gallery->user_count(), 1);
  int added = 0;
  for (int i = 0; i < 20; ++i) added += count(f.step({body(5, kRed, kBlue, View::SL, 20 + i)}).events, ReidEventKind::kViewAdded);
  EXPECT_EQ(added, 1);
  EXPECT_EQ(f.gallery->user_scans(1).size(), 2u);
  // A scan that looks like someone else is not added to this user.
  for (int i = 0; i < 20; ++i) added += count(f.step({body(5, kGreen, kYellow, View::B, 40 + i)}).events, ReidEventKind::kViewAdded);
  EXPECT_EQ(added, 1);
}

TEST(OnlineReid, ATrackThatJumpsToSomeoneElseIsReleasedAndDecidedAgain) {
  Fixture f;
  for (int i = 0; i < 5; ++i) f.step({body(4, kRed, kBlue, View::F, i)});
  ASSERT_EQ(f.gallery->user_count(), 1);
  // The sensor's track 4 now follows another person (an id swap after an occlusion).
  std::vector<ReidEvent> events;
  std::optional<UserId> now;
  for (int i = 0; i < 40; ++i) {
    const ReidStep s = f.step({body(4, kGreen, kYellow, View::F, 10 + i)});
    events.insert(events.end(), s.events.begin(), s.events.end());
    now = s.identities[0].user;
  }
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events[0].kind, ReidEventKind::kLeft);
  EXPECT_EQ(events[0].user, 1);
  EXPECT_EQ(events[1].kind, ReidEventKind::kEnrolled);
  EXPECT_EQ(now, 2);
  // The first user's gallery entry kept only their own scan.
  EXPECT_EQ(f.gallery->user_scans(1).size(), 1u);
}

TEST(OnlineReid, FinishDecidesPendingTracksAndEndsEveryone) {
  Fixture f;
  f.step({body(1, kRed, kBlue, View::F, 0), body(2, kGreen, kYellow, View::F, 1)});
  const std::vector<ReidEvent> events = f.reid->finish();
  EXPECT_EQ(count(events, ReidEventKind::kEnrolled), 2);
  EXPECT_EQ(count(events, ReidEventKind::kLeft), 2);
  EXPECT_EQ(f.reid->live_tracks(), 0u);
  // The gallery's own history holds the same events.
  int left = 0;
  for (const Event& e : f.gallery->events()) left += e.kind == EventKind::kLeft;
  EXPECT_EQ(left, 2);
}

TEST(OnlineReid, OptionsAreChecked) {
  OnlineReidOptions o;
  o.decide_after = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.min_quality = 1.5;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.margin = -1;
  EXPECT_THROW(o.check(), UsageError);
  EXPECT_NO_THROW(OnlineReidOptions{}.check());
}

}  // namespace
}  // namespace bodyrec
