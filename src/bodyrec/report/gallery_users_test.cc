#include "bodyrec/report/gallery_users.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "report_fixture.h"
#include "test_support.h"

namespace bodyrec::report {
namespace {

using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;

constexpr double kT0 = 1795179600.0;  // the fixture's 2026-11-20T13:00:00Z

TEST(GalleryUsers, ReadsUsersViewsTimesAndEvents) {
  TempDir dir;
  bodyrec::testing::write_gallery(dir / "g.db");
  const auto users = read_gallery_users((dir / "g.db").string());
  ASSERT_EQ(users.size(), 2u);
  const ReportUser& alice = users[0];
  EXPECT_EQ(alice.id, 1);
  EXPECT_EQ(alice.label, "alice");
  EXPECT_EQ(alice.first_seen, kT0);
  EXPECT_EQ(alice.last_seen, kT0 + 300);  // recognised at 13:05
  // kAllViews order F FR FL SR SL B BR BL: F (0), SR (3), B (5).
  const std::array<bool, 8> alice_views = {true, false, false, true, false, true, false, false};
  EXPECT_EQ(alice.scanned, alice_views);
  for (int v = 0; v < 8; ++v) EXPECT_EQ(alice.views[v].empty(), !alice_views[v]) << v;
  // The body keeps its cyan; outside the mask the slot colour replaces the black background.
  EXPECT_EQ(alice.views[0].size(), cv::Size(64, 128));
  EXPECT_EQ(alice.views[0].at<cv::Vec3b>(64, 32), cv::Vec3b(255, 255, 0));
  EXPECT_EQ(alice.views[0].at<cv::Vec3b>(0, 0), cv::Vec3b(249, 245, 241));
  ASSERT_EQ(alice.events.size(), 2u);
  EXPECT_EQ(alice.events[0].kind, "enrolled");
  EXPECT_EQ(alice.events[0].view, "F");
  EXPECT_EQ(alice.events[0].time, kT0);
  EXPECT_EQ(*alice.events[0].track, 7);
  EXPECT_EQ(alice.events[0].source, "fixture");
  EXPECT_EQ(alice.events[1].kind, "recognised");
  EXPECT_EQ(*alice.events[1].score, 0.87);
  const ReportUser& bob = users[1];
  EXPECT_EQ(bob.label, "bob");
  EXPECT_EQ(bob.first_seen, kT0 + 600);
  EXPECT_EQ(bob.last_seen, kT0 + 600);
  EXPECT_TRUE(bob.scanned[7]);
  EXPECT_FALSE(bob.views[7].empty());
  EXPECT_EQ(bob.events.size(), 1u);
}

TEST(GalleryUsers, WithoutImagesOnlyWhichViewsHaveScans) {
  TempDir dir;
  bodyrec::testing::write_gallery(dir / "g.db");
  bodyrec::testing::write_gallery(dir / "features-only.db", false);
  for (const auto& [file, images] : {std::pair{"g.db", false}, std::pair{"features-only.db", true}}) {
    const auto users = read_gallery_users((dir / file).string(), images);
    ASSERT_EQ(users.size(), 2u) << file;
    EXPECT_TRUE(users[0].scanned[0] && users[0].scanned[3] && users[0].scanned[5]) << file;
    for (const auto& u : users)
      for (const auto& v : u.views) EXPECT_TRUE(v.empty()) << file;
  }
}

TEST(GalleryUsers, BadGalleriesAreTheStoresInputErrors) {
  TempDir dir;
  const std::string missing = (dir / "none.db").string();
  EXPECT_EQ(input_error([&] { read_gallery_users(missing); }), missing + ": gallery not found");
  EXPECT_FALSE(std::filesystem::exists(missing));
  bodyrec::testing::write_text(dir / "notes.db", "just some text, not a database\n");
  EXPECT_NE(input_error([&] { read_gallery_users((dir / "notes.db").string()); }).find("not an SQLite database"),
            std::string::npos);
}

}  // namespace
}  // namespace bodyrec::report
