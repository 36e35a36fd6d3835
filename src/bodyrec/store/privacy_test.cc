// Issue 7 privacy: erased images and features leave no bytes in the gallery file or its WAL.
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::TempDir;
using store::testing::make_scan;

std::string raw_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The .db plus its -wal, if any: everything SQLite keeps on disk for this gallery.
std::string gallery_bytes(const std::string& path) { return raw_bytes(path) + raw_bytes(path + "-wal"); }

// 24 bytes from the middle of the scan's PNG encoding (random pixels: unique to this image), and 24
// bytes of its feature blob's data.
struct Patterns {
  std::string image, features;
};

Patterns patterns_of(const GalleryScan& scan) {
  std::vector<unsigned char> png;
  cv::imencode(".png", scan.image, png);
  const auto blob = store::encode_features(scan.features);
  return {std::string(png.begin() + static_cast<long>(png.size() / 2), png.begin() + static_cast<long>(png.size() / 2) + 24),
          std::string(blob.begin() + 16, blob.begin() + 40)};
}

GalleryScan distinct_scan(int seed) {
  GalleryScan scan = make_scan(View::F, 0.5, seed, 96, 48);
  cv::RNG rng(static_cast<uint64_t>(seed) + 99);
  rng.fill(scan.features, cv::RNG::UNIFORM, 0.0, 1.0);
  return scan;
}

TEST(GalleryPrivacy, ForgetLeavesNoImageOrFeatureBytesInTheFiles) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  Gallery g(path, [] { GalleryOptions o; o.create = true; return o; }());
  const GalleryScan secret = distinct_scan(1), other = distinct_scan(2);
  const Patterns p = patterns_of(secret), q = patterns_of(other);
  const UserId u = g.enrol(secret);
  g.enrol(other);
  // The patterns are there before (else the test could not fail).
  std::string bytes = gallery_bytes(path);
  ASSERT_NE(bytes.find(p.image), std::string::npos);
  ASSERT_NE(bytes.find(p.features), std::string::npos);
  const EraseReport r = g.forget(u);
  EXPECT_TRUE(r.checkpointed);
  bytes = gallery_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(p.features), std::string::npos);
  // The other user's data is intact.
  EXPECT_NE(bytes.find(q.image), std::string::npos);
  EXPECT_EQ(g.user_count(), 1);
}

TEST(GalleryPrivacy, ReplacedAndPurgedScansLeaveNoBytes) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  Gallery g(path, [] { GalleryOptions o; o.create = true; return o; }());
  GalleryScan first = distinct_scan(3), better = distinct_scan(4);
  better.quality = 0.9;
  const Patterns p = patterns_of(first), b = patterns_of(better);
  const UserId u = g.enrol(first);
  EXPECT_EQ(g.put_scan(u, better), PutResult::kReplaced);
  g.purge();
  const std::string bytes = gallery_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(b.image), std::string::npos);
  EXPECT_EQ(bytes.find(b.features), std::string::npos);
}

// Retention (prune --unseen-for, reid --prune-unseen-for) scrubs like forget.
TEST(GalleryPrivacy, PrunedUsersLeaveNoBytes) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  Gallery g(path, [] { GalleryOptions o; o.create = true; return o; }());
  GalleryScan stale = distinct_scan(5), recent = distinct_scan(6);
  stale.time = from_unix_ms(1000);
  recent.time = from_unix_ms(9000000);
  const Patterns p = patterns_of(stale), q = patterns_of(recent);
  g.enrol(stale);
  g.enrol(recent);
  ASSERT_NE(gallery_bytes(path).find(p.image), std::string::npos);
  const EraseReport r = g.prune_unseen(std::chrono::seconds(3600), from_unix_ms(9000000));
  EXPECT_EQ(r.users.size(), 1u);
  EXPECT_TRUE(r.checkpointed);
  const std::string bytes = gallery_bytes(path);
  EXPECT_EQ(bytes.find(p.image), std::string::npos);
  EXPECT_EQ(bytes.find(p.features), std::string::npos);
  EXPECT_NE(bytes.find(q.image), std::string::npos);
  EXPECT_EQ(g.user_count(), 1);
}

TEST(GalleryPrivacy, NoImagesStoresNoPixels) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  {
    GalleryOptions o;
    o.create = true;
    o.store_images = false;
    Gallery g(path, o);
    for (int i = 0; i < 5; ++i) g.enrol(distinct_scan(10 + i));
  }
  const std::string bytes = gallery_bytes(path);
  EXPECT_EQ(bytes.find("\x89PNG"), std::string::npos);
  EXPECT_EQ(bytes.find("IDAT"), std::string::npos);
  // ... but the features are there.
  EXPECT_NE(bytes.find(patterns_of(distinct_scan(12)).features), std::string::npos);
}

}  // namespace
}  // namespace bodyrec
