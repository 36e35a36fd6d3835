#include "bodyrec/reid/colour_reid_pipeline.h"

#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/memory_reid_store.h"

namespace bodyrec {
namespace {

// A static textured background (640x360) with one upright "person" (a coloured body below a skin-toned
// head) at `p`, or nobody when p is empty.
cv::Mat scene(const cv::Rect& p, const cv::Scalar& shirt, const cv::Scalar& trousers) {
  cv::Mat img(360, 640, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(img, cv::RNG::UNIFORM, cv::Scalar(90, 90, 90), cv::Scalar(150, 150, 150));
  cv::GaussianBlur(img, img, {5, 5}, 2);
  if (p.empty()) return img;
  const int head = p.height / 6, torso = (p.height - head) / 2;
  cv::rectangle(img, cv::Rect(p.x + p.width * 3 / 10, p.y, p.width * 4 / 10, head), cv::Scalar(80, 130, 200),
                cv::FILLED);
  cv::rectangle(img, cv::Rect(p.x, p.y + head, p.width, torso), shirt, cv::FILLED);
  cv::rectangle(img, cv::Rect(p.x, p.y + head + torso, p.width, p.height - head - torso), trousers, cv::FILLED);
  return img;
}

struct Walk {
  cv::Scalar shirt, trousers;
  int step_px;  // per frame; > 0 walks to the image's right
};

// Warm-up frames of the empty scene, then each walker crosses the frame alone, with empty frames between.
std::vector<Frame> walks(const std::vector<Walk>& people) {
  std::vector<Frame> frames;
  const auto add = [&](const cv::Mat& img) {
    Frame f;
    f.image = img;
    f.index = static_cast<int>(frames.size());
    f.time_s = f.index / 25.0;
    f.name = "walks";
    frames.push_back(f);
  };
  for (int i = 0; i < 15; ++i) add(scene({}, {}, {}));
  for (const Walk& w : people) {
    for (int i = 0; i < 60; ++i) {
      const int x = w.step_px > 0 ? 20 + w.step_px * i : 570 + w.step_px * i;
      add(scene({x, 150, 50, 160}, w.shirt, w.trousers));
    }
    for (int i = 0; i < 40; ++i) add(scene({}, {}, {}));
  }
  return frames;
}

ColourReidOptions quiet_options() {
  ColourReidOptions o;
  o.views.use_faces = false;  // drawn heads have no faces
  o.reid.stature_wait_frames = 0;
  return o;
}

TEST(ColourReidPipeline, OneWalkerIsEnrolledOnceWithASideViewAndLeaves) {
  ForegroundPeopleDetector people;
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ColourReidPipeline reid(people, store, *matcher, quiet_options());
  int enrolled = 0, with_body = 0, left = 0;
  std::set<View> views;
  for (const Frame& f : walks({{{200, 60, 30}, {40, 40, 40}, 8}})) {
    const ColourReidResult r = reid.process(f);
    ASSERT_EQ(r.bodies.size(), r.step.identities.size());
    with_body += !r.bodies.empty();
    for (const ColourBody& b : r.bodies)
      if (b.view.view) views.insert(*b.view.view);
    for (const ReidEvent& e : r.step.events) {
      enrolled += e.kind == ReidEventKind::kEnrolled;
      left += e.kind == ReidEventKind::kLeft;
    }
  }
  for (const ReidEvent& e : reid.finish()) left += e.kind == ReidEventKind::kLeft;
  EXPECT_EQ(enrolled, 1);
  EXPECT_GE(left, 1);
  EXPECT_GE(with_body, 40);  // of the walker's 60 frames
  // Walking to the image's right: the body faces the image's right (yaw -90).
  EXPECT_TRUE(views.count(view_of_yaw(-90.0))) << views.size();
  EXPECT_FALSE(views.count(View::F));
  EXPECT_FALSE(views.count(View::B));
}

// The decisions of walks red, green, red: two enrolments of two users, then the first one recognised.
void expect_red_green_red(const std::vector<ReidEvent>& decisions) {
  ASSERT_EQ(decisions.size(), 3u);
  EXPECT_EQ(decisions[0].kind, ReidEventKind::kEnrolled);
  EXPECT_EQ(decisions[1].kind, ReidEventKind::kEnrolled);
  EXPECT_NE(decisions[1].user, decisions[0].user);
  EXPECT_EQ(decisions[2].kind, ReidEventKind::kRecognised);
  EXPECT_EQ(decisions[2].user, decisions[0].user);
}

TEST(ColourReidPipeline, AReturningWalkerIsRecognisedAndANewOneEnrolled) {
  ForegroundPeopleDetector people;
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ColourReidPipeline reid(people, store, *matcher, quiet_options());
  std::vector<ReidEvent> decisions;
  const Walk red{{30, 30, 210}, {150, 40, 30}, 8}, green{{40, 190, 40}, {30, 30, 30}, 8};
  for (const Frame& f : walks({red, green, red}))
    for (const ReidEvent& e : reid.process(f).step.events)
      if (e.kind == ReidEventKind::kEnrolled || e.kind == ReidEventKind::kRecognised) decisions.push_back(e);
  expect_red_green_red(decisions);
}

// One walk whose body changes clothes half-way: what a tracker that jumped to someone else gives.
std::vector<Frame> swapped_walk() {
  std::vector<Frame> frames = walks({});
  for (int i = 0; i < 70; ++i) {
    const bool red = i < 35;
    Frame f;
    f.image = scene({20 + 7 * i, 150, 50, 160}, red ? cv::Scalar(30, 30, 210) : cv::Scalar(40, 190, 40),
                    red ? cv::Scalar(150, 40, 30) : cv::Scalar(30, 200, 220));
    f.index = static_cast<int>(frames.size());
    f.time_s = f.index / 25.0;
    f.name = "swap";
    frames.push_back(f);
  }
  return frames;
}

TEST(ColourReidPipeline, ATrackThatTurnsIntoSomeoneElseGetsANewKeyAndUser) {
  for (const bool enabled : {true, false}) {
    ForegroundPeopleDetector people;
    MemoryReidStore store;
    auto matcher = make_matcher("stripes");
    ColourReidOptions o = quiet_options();
    o.segments.enabled = enabled;
    ColourReidPipeline reid(people, store, *matcher, o);
    std::set<uint64_t> tracks, keys;
    std::set<UserId> enrolled;
    for (const Frame& f : swapped_walk()) {
      const ColourReidResult r = reid.process(f);
      for (const ColourBody& b : r.bodies) tracks.insert(b.track), keys.insert(b.key);
      for (const ReidEvent& e : r.step.events)
        if (e.kind == ReidEventKind::kEnrolled) enrolled.insert(e.user);
    }
    SCOPED_TRACE(enabled);
    ASSERT_EQ(tracks.size(), 1u);  // the tracker keeps one id throughout
    if (enabled) {
      EXPECT_EQ(reid.segments().cuts(), 1);
      EXPECT_EQ(keys, (std::set<uint64_t>{*tracks.begin(), *tracks.begin() + (1ull << 32)}));
      EXPECT_EQ(enrolled.size(), 2u);
    } else {
      EXPECT_EQ(keys, tracks);
      EXPECT_EQ(reid.segments().cuts(), 0);
    }
  }
}

TEST(ColourReidPipeline, GivenBodiesKeepTheirTrackIdsAndAreDecidedAsDetectedOnes) {
  ForegroundPeopleDetector people;
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ColourReidPipeline reid(people, store, *matcher, quiet_options());
  const Walk red{{30, 30, 210}, {150, 40, 30}, 8}, green{{40, 190, 40}, {30, 30, 30}, 8};
  const std::vector<Frame> frames = walks({red, green, red});
  std::vector<ReidEvent> decisions;
  std::set<uint64_t> keys;
  for (size_t i = 0; i < frames.size(); ++i) {
    // Each walk's frames (after 15 of warm-up: 60 walking, 40 empty) give the drawn person as a body.
    std::vector<ColourReidPipeline::GivenBody> given;
    const int walk = (static_cast<int>(i) - 15) / 100, step = (static_cast<int>(i) - 15) % 100;
    if (i >= 15 && step < 60) {
      const cv::Rect box(20 + 8 * step, 150, 50, 160);
      given.push_back({static_cast<uint64_t>(100 + walk), box, cv::Mat(box.size(), CV_8U, cv::Scalar(255))});
    }
    const ColourReidResult r = reid.process(frames[i], given);
    ASSERT_EQ(r.bodies.size(), given.size());
    for (const ColourBody& b : r.bodies) keys.insert(b.key);
    for (const ReidEvent& e : r.step.events)
      if (e.kind == ReidEventKind::kEnrolled || e.kind == ReidEventKind::kRecognised) decisions.push_back(e);
  }
  EXPECT_EQ(keys, (std::set<uint64_t>{100, 101, 102}));
  expect_red_green_red(decisions);
  // A mask that does not fit its box is refused.
  const cv::Rect box(20, 150, 50, 160);
  EXPECT_THROW(reid.process(frames[20], {{7, box, cv::Mat(10, 10, CV_8U, cv::Scalar(255))}}), InputError);
}

TEST(ColourReidPipeline, BadOptionsAndFramesAreRefused) {
  ForegroundPeopleDetector people;
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ColourReidOptions o = quiet_options();
  o.views.window_s = -1;
  EXPECT_THROW(ColourReidPipeline(people, store, *matcher, o), UsageError);
  ColourReidPipeline reid(people, store, *matcher, quiet_options());
  Frame grey;
  grey.image = cv::Mat(100, 100, CV_8UC1, cv::Scalar(0));
  grey.name = "grey.png";
  EXPECT_THROW(reid.process(grey), InputError);
}

}  // namespace
}  // namespace bodyrec
