// Several sensors on one gallery (issue 47), the same on both databases (instantiated for SQLite in
// gallery_reid_store_test.cc, for PostgreSQL in reid_sites_server_test.cc): each run takes in the users,
// views and erasures other runs make while it runs, and two runs that meet the same new person at the same
// moment make one user.
#include <condition_variable>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/reid/online_reid.h"
#include "bodyrec/reid/stripe_features.h"
#include "bodyrec/reid/reid_sites_test_support.h"
#include "reid_bodies.h"

namespace bodyrec::store::testing {
namespace {

using bodyrec::testing::body;
using bodyrec::testing::kBlue;
using bodyrec::testing::kGreen;
using bodyrec::testing::kRed;
using bodyrec::testing::kYellow;

// One sensor's run: its own connection to the gallery, its own matcher and decisions.
struct Sensor {
  Gallery gallery;
  std::unique_ptr<AppearanceMatcher> matcher = make_matcher("stripes");
  GalleryReidStore store;
  OnlineReid reid;
  Sensor(const std::string& path, const std::string& name)
      : gallery(path, options(name)), store(gallery, *matcher), reid(store, *matcher) {}
  static GalleryOptions options(const std::string& name) {
    GalleryOptions o;
    o.sensor = name;
    o.sync_full = false;
    return o;
  }
};

// The store of a run whose refresh at the start of a frame came just before another run's commit: outside
// exclusive() it takes in nothing new, so only the check inside exclusive() can see that commit.
class LateStore : public ReidStore {
 public:
  explicit LateStore(ReidStore& inner) : inner_(inner) {}
  const std::vector<GalleryEntry>& scans(View view) const override { return inner_.scans(view); }
  const GalleryEntry* find(UserId user, View view) const override { return inner_.find(user, view); }
  UserId enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) override {
    return inner_.enrol(scans, track, time_s);
  }
  std::optional<PutResult> put_scan(UserId user, const GalleryScan& scan, double time_s) override {
    return inner_.put_scan(user, scan, time_s);
  }
  bool log(const ReidEvent& event, double time_s) override { return inner_.log(event, time_s); }
  bool refresh() override { return inside_ && inner_.refresh(); }
  bool has_user(UserId user) const override { return inner_.has_user(user); }
  void exclusive(const std::function<void()>& body) override {
    inner_.exclusive([&] {
      inside_ = true;
      try {
        body();
      } catch (...) {
        inside_ = false;
        throw;
      }
      inside_ = false;
    });
  }

 private:
  ReidStore& inner_;
  bool inside_ = false;
};

std::vector<ReidEvent> of_kind(const std::vector<ReidEvent>& events, ReidEventKind kind) {
  std::vector<ReidEvent> out;
  for (const ReidEvent& e : events)
    if (e.kind == kind) out.push_back(e);
  return out;
}

TEST_P(ReidSites, ARunTakesInOthersUsersViewsAndErasuresWhileItRuns) {
  const std::string path = gallery();
  Sensor a(path, "door"), b(path, "hall");  // both open before anyone is enrolled
  int frame = 0;
  const auto at = [&](Sensor& s, const ReidBody& person) { return s.reid.step(frame / 30.0, {person}); };
  // The door enrols a person; the hall, open all along, recognises them at its first decision.
  for (int i = 0; i < 6; ++i, ++frame) at(a, body(1, kRed, kBlue, View::F, frame));
  ASSERT_EQ(a.gallery.user_count(), 1);
  std::vector<ReidEvent> hall;
  for (int i = 0; i < 6; ++i, ++frame)
    for (const ReidEvent& e : at(b, body(5, kRed, kBlue, View::F, frame)).events) hall.push_back(e);
  EXPECT_TRUE(of_kind(hall, ReidEventKind::kEnrolled).empty());
  const auto recognised = of_kind(hall, ReidEventKind::kRecognised);
  ASSERT_EQ(recognised.size(), 1u);
  EXPECT_EQ(recognised[0].user, 1);
  // The hall adds the person's back; the door takes it in (its cache holds the view without a reload of
  // its own making).
  for (int i = 0; i < 12; ++i, ++frame) at(b, body(5, kRed, kBlue, View::B, frame));
  ASSERT_NE(b.gallery.find(1, View::B), nullptr);
  at(a, body(1, kRed, kBlue, View::F, frame++));
  EXPECT_NE(a.gallery.find(1, View::B), nullptr);
  // An administrator forgets the person while both still see them: neither writes them back.
  {
    Gallery admin(path);
    admin.forget(1);
  }
  for (int i = 0; i < 8; ++i, ++frame) {
    at(a, body(1, kRed, kBlue, View::F, frame));
    at(b, body(5, kRed, kBlue, View::B, frame));
  }
  for (int i = 0; i < 40; ++i, ++frame) {
    a.reid.step(frame / 30.0, {});
    b.reid.step(frame / 30.0, {});
  }
  a.reid.finish();
  b.reid.finish();
  Gallery check(path);
  EXPECT_FALSE(check.user(1));
  EXPECT_TRUE(check.user_scans(1).empty());
  for (const Event& e : check.events()) EXPECT_NE(e.user, std::optional<UserId>(1)) << event_kind_name(e.kind);
  // The person, decided afresh at both sensors after the erasure, is one new user.
  EXPECT_EQ(check.user_count(), 1);
}

// Two sensors decide on the same new person, the second's view of the gallery taken just before the
// first one's enrolment: the second checks again under the write lock and recognises the new user.
TEST_P(ReidSites, AnEnrolmentCommittedSinceTheFrameBeganIsRecognisedNotEnrolledAgain) {
  const std::string path = gallery();
  Sensor a(path, "door"), b(path, "hall");
  LateStore late(b.store);
  OnlineReid b_late(late, *b.matcher);
  std::vector<ReidEvent> door, hall;
  for (int frame = 0; frame < 6; ++frame) {
    for (const ReidEvent& e : a.reid.step(frame / 30.0, {body(1, kRed, kBlue, View::F, frame)}).events) door.push_back(e);
    for (const ReidEvent& e : b_late.step(frame / 30.0, {body(2, kRed, kBlue, View::F, 100 + frame)}).events)
      hall.push_back(e);
  }
  ASSERT_EQ(of_kind(door, ReidEventKind::kEnrolled).size(), 1u);
  EXPECT_TRUE(of_kind(hall, ReidEventKind::kEnrolled).empty());
  const auto recognised = of_kind(hall, ReidEventKind::kRecognised);
  ASSERT_EQ(recognised.size(), 1u);
  EXPECT_EQ(recognised[0].user, 1);
  EXPECT_EQ(a.gallery.user_count(), 1);
  // A new person at the hall alone is still enrolled there, with the next id.
  std::optional<UserId> user;
  for (int frame = 6; frame < 16 && !user; ++frame)
    user = b_late.step(frame / 30.0, {body(3, kGreen, kYellow, View::F, frame)}).identities[0].user;
  EXPECT_EQ(user, 2);
}

// Two runs in two threads, each with its own connection, meet the same new person in the same frames.
TEST_P(ReidSites, TwoSensorsMeetingANewPersonAtOnceMakeOneUser) {
  for (int round = 0; round < 3; ++round) {
    const std::string path = gallery();
    Sensor a(path, "door"), b(path, "hall");
    // Both threads take each frame together.
    std::mutex m;
    std::condition_variable cv;
    int arrived = 0, generation = 0;
    const auto together = [&] {
      std::unique_lock<std::mutex> lock(m);
      const int g = generation;
      if (++arrived == 2) {
        arrived = 0;
        ++generation;
        cv.notify_all();
      } else {
        cv.wait(lock, [&] { return generation != g; });
      }
    };
    std::vector<ReidEvent> events[2];
    const auto run = [&](Sensor& s, uint64_t track, int seed, std::vector<ReidEvent>& out) {
      for (int frame = 0; frame < 8; ++frame) {
        together();
        for (const ReidEvent& e : s.reid.step(frame / 30.0, {body(track, kRed, kBlue, View::F, seed + frame)}).events)
          out.push_back(e);
      }
    };
    std::thread door([&] { run(a, 1, 0, events[0]); });
    std::thread hall([&] { run(b, 2, 100, events[1]); });
    door.join();
    hall.join();
    Gallery check(path);
    EXPECT_EQ(check.user_count(), 1) << "round " << round;
    const size_t enrolled = of_kind(events[0], ReidEventKind::kEnrolled).size() +
                            of_kind(events[1], ReidEventKind::kEnrolled).size();
    const size_t recognised = of_kind(events[0], ReidEventKind::kRecognised).size() +
                              of_kind(events[1], ReidEventKind::kRecognised).size();
    EXPECT_EQ(enrolled, 1u) << "round " << round;
    EXPECT_EQ(recognised, 1u) << "round " << round;
  }
}

}  // namespace
}  // namespace bodyrec::store::testing
