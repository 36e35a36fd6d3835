// Issue 7 privacy, on both databases (issue 47): erased images and features leave no bytes in the
// gallery's files (SQLite: the .db and its -wal; PostgreSQL: the database's table files, after the
// CHECKPOINT a test runs to flush what is still in memory). PostgreSQL's WAL and pg_dump are in
// gallery_server_test.cc.
#include <gtest/gtest.h>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec::store::testing {
namespace {

TEST_P(GalleryPrivacy, ForgetLeavesNoImageOrFeatureBytesInTheFiles) {
  const std::string path = fresh();
  Gallery g(path, creating());
  const GalleryScan secret = distinct_scan(1), other = distinct_scan(2);
  const Patterns p = patterns_of(secret), q = patterns_of(other);
  const UserId u = g.enrol(secret);
  g.enrol(other);
  // The patterns are there before (else the test could not fail).
  std::string bytes = stored_bytes(path);
  ASSERT_NE(bytes.find(p.image), std::string::npos);
  ASSERT_NE(bytes.find(p.features), std::string::npos);
  const EraseReport r = g.forget(u);
  EXPECT_TRUE(r.checkpointed);
  bytes = stored_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(p.features), std::string::npos);
  // The other user's data is intact.
  EXPECT_NE(bytes.find(q.image), std::string::npos);
  EXPECT_EQ(g.user_count(), 1);
}

TEST_P(GalleryPrivacy, ReplacedAndPurgedScansLeaveNoBytes) {
  const std::string path = fresh();
  Gallery g(path, creating());
  GalleryScan first = distinct_scan(3), better = distinct_scan(4);
  better.quality = 0.9;
  const Patterns p = patterns_of(first), b = patterns_of(better);
  const UserId u = g.enrol(first);
  EXPECT_EQ(g.put_scan(u, better), PutResult::kReplaced);
  g.purge();
  const std::string bytes = stored_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(b.image), std::string::npos);
  EXPECT_EQ(bytes.find(b.features), std::string::npos);
}

// Retention (prune --unseen-for, reid --prune-unseen-for) scrubs like forget.
TEST_P(GalleryPrivacy, PrunedUsersLeaveNoBytes) {
  const std::string path = fresh();
  Gallery g(path, creating());
  GalleryScan stale = distinct_scan(5), recent = distinct_scan(6);
  stale.time = from_unix_ms(1000);
  recent.time = from_unix_ms(9000000);
  const Patterns p = patterns_of(stale), q = patterns_of(recent);
  g.enrol(stale);
  g.enrol(recent);
  ASSERT_NE(stored_bytes(path).find(p.image), std::string::npos);
  const EraseReport r = g.prune_unseen(std::chrono::seconds(3600), from_unix_ms(9000000));
  EXPECT_EQ(r.users.size(), 1u);
  EXPECT_TRUE(r.checkpointed);
  const std::string bytes = stored_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(p.features), std::string::npos);
  EXPECT_NE(bytes.find(q.image), std::string::npos);
  EXPECT_EQ(g.user_count(), 1);
}

TEST_P(GalleryPrivacy, NoImagesStoresNoPixels) {
  const std::string path = fresh();
  {
    GalleryOptions o;
    o.create = true;
    o.store_images = false;
    Gallery g(path, o);
    for (int i = 0; i < 5; ++i) g.enrol(distinct_scan(10 + i));
  }
  const std::string bytes = stored_bytes(path);
  EXPECT_EQ(bytes.find("\x89PNG"), std::string::npos);
  EXPECT_EQ(bytes.find("IDAT"), std::string::npos);
  // ... but the features are there.
  EXPECT_NE(bytes.find(patterns_of(distinct_scan(12)).features), std::string::npos);
}

}  // namespace
}  // namespace bodyrec::store::testing
