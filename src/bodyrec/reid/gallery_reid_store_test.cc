// Online re-identification on a persistent gallery: old descriptors described again, times from the
// source's clock, and erasures by another connection (another process) while a run is open.
#include "bodyrec/reid/gallery_reid_store.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/online_reid.h"
#include "bodyrec/reid/reid_sites_test_support.h"
#include "bodyrec/reid/stripe_features.h"
#include "reid_bodies.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::body;
using testing::kBlue;
using testing::kGreen;
using testing::kRed;
using testing::kYellow;

GalleryOptions quick() {
  GalleryOptions go;
  go.create = true;
  go.sync_full = false;
  return go;
}

TEST(GalleryReidStore, ScansOfAnOlderDescriptorAreDescribedAgainOrRefused) {
  const ReidBody person = body(1, kRed, kBlue, View::F, 0);
  const auto old_scan = [&] {
    GalleryScan g;
    g.view = View::F;
    g.image = person.scan->image;
    g.mask = person.scan->mask;
    g.features = cv::Mat(1, 1024, CV_32F, cv::Scalar(0.01));  // 8 stripes x 128 bins, as stripes1 stored
    g.descriptor = "stripes/stripes1";
    g.descriptor_version = 1;
    g.quality = 0.7;
    return g;
  };
  testing::TempDir dir;
  GalleryOptions go;
  go.create = true;
  go.sync_full = false;
  auto matcher = make_matcher("stripes");
  {
    Gallery g((dir.path() / "with-images.db").string(), go);
    g.enrol(old_scan());
    GalleryScan other = old_scan();  // another matcher's scan (a run with another --matcher): described too
    other.view = View::B;
    other.descriptor = "kaze/kaze1";
    g.put_scan(1, other);
    EXPECT_EQ(redescribe_old_scans(g, *matcher), 2);
    const std::vector<StoredScan> scans = g.user_scans(1);
    ASSERT_EQ(scans.size(), 2u);
    for (const StoredScan& s : scans) {
      EXPECT_EQ(s.descriptor, "stripes/stripes2");
      EXPECT_EQ(s.descriptor_version, kReidDescriptorVersion);
      EXPECT_EQ(static_cast<int>(s.features.total()), stripe_length() + kBodyFeatures);
      EXPECT_DOUBLE_EQ(s.quality, 0.7);
    }
    EXPECT_EQ(redescribe_old_scans(g, *matcher), 0);  // done once
    // The person, back, is recognised against the described-again scan.
    GalleryReidStore store(g, *matcher);
    OnlineReid reid(store, *matcher);
    std::optional<UserId> user;
    for (int i = 0; i < 6; ++i) user = reid.step(i / 30.0, {body(9, kRed, kBlue, View::F, 10 + i)}).identities[0].user;
    EXPECT_EQ(user, 1);
  }
  go.store_images = false;
  const std::string path = (dir.path() / "features-only.db").string();
  Gallery g(path, go);
  g.enrol(old_scan());
  try {
    GalleryReidStore store(g, *matcher);
    ADD_FAILURE() << "an old scan without its image was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("--no-images"), std::string::npos) << what;
    EXPECT_NE(what.find("stripes/stripes1"), std::string::npos) << what;
  }
}

TEST(GalleryReidStore, TimesComeFromTheSourcesClock) {
  testing::TempDir dir;
  Gallery g((dir.path() / "g.db").string(), quick());
  auto matcher = make_matcher("stripes");
  GalleryReidStoreOptions so;
  so.source = "rec";
  so.start = GalleryTime(std::chrono::milliseconds(1700000000000));  // 2023-11-14T22:13:20Z
  GalleryReidStore store(g, *matcher, so);
  OnlineReid reid(store, *matcher);
  for (int i = 0; i < 6; ++i) reid.step(10 + i / 30.0, {body(1, kRed, kBlue, View::F, i)});
  const std::vector<Event> events = g.events();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events[0].kind, EventKind::kEnrolled);
  EXPECT_EQ(events[0].source, "rec");
  // Enrolled at the fourth scan: frame 3, 10.1 s into the recording.
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::milliseconds>(events[0].time.time_since_epoch()).count(),
            1700000000000 + 10100);
  const std::optional<User> user = g.user(1);
  ASSERT_TRUE(user);
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::milliseconds>(user->first_seen.time_since_epoch()).count(),
            1700000000000 + 10100);
}

TEST(GalleryReidStore, AForgetFromAnotherConnectionDoesNotStopTheRunAndIsNotWrittenBack) {
  testing::TempDir dir;
  const std::string path = (dir.path() / "g.db").string();
  Gallery running(path, quick());
  auto matcher = make_matcher("stripes");
  GalleryReidStore store(running, *matcher);
  OnlineReid reid(store, *matcher);
  int frame = 0;
  const auto step = [&](uint64_t track, View view) { return reid.step(frame / 30.0, {body(track, kRed, kBlue, view, frame++)}); };
  for (int i = 0; i < 6; ++i) step(7, View::F);
  ASSERT_EQ(running.user_count(), 1);
  {
    Gallery other(path, GalleryOptions{});  // `bodyrec gallery forget 1` in another process
    other.forget(1);
  }
  // The run goes on: the body shows its back (a view user 1 lacked), is decided afresh, enrolled anew.
  std::optional<UserId> user;
  for (int i = 0; i < 30 && !user; ++i) user = step(7, View::B).identities[0].user;
  EXPECT_EQ(user, 2);
  for (int i = 0; i < 40; ++i) reid.step(frame++ / 30.0, {});
  reid.finish();
  EXPECT_FALSE(running.user(1));
  EXPECT_TRUE(running.user_scans(1).empty());
  for (const Event& e : running.events()) EXPECT_NE(e.user, std::optional<UserId>(1)) << event_kind_name(e.kind);
  EXPECT_EQ(running.integrity_check(), "ok");
}

}  // namespace
}  // namespace bodyrec

namespace bodyrec::store::testing {

// The several-sensors suite (reid_sites_suite_test.cc) on SQLite files.
INSTANTIATE_TEST_SUITE_P(Db, ReidSites, ::testing::Values(sql::Dialect::kSqlite), backend_name);

}  // namespace bodyrec::store::testing
