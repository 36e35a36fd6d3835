// The gallery on SQLite: file permissions, files that are not galleries, and the SQLite instantiation of
// the suites every database passes (gallery_suite_test.cc, privacy_suite_test.cc,
// crash_safety_suite_test.cc).
#include "bodyrec/store/gallery.h"

#include <sqlite3.h>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec::store::testing {
BODYREC_INSTANTIATE_GALLERY_SUITES(sql::Dialect::kSqlite);
}  // namespace bodyrec::store::testing

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;

GalleryOptions creating() {
  GalleryOptions o;
  o.create = true;
  return o;
}

// Raw SQL on a file, bypassing the gallery (to fake other applications and newer versions).
void raw_exec(const std::string& path, const char* sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_close(db);
}

int file_mode(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return -1;
  return static_cast<int>(st.st_mode & 0777);
}

TEST(Gallery, NewFileIsTheCurrentSchemaAndOwnerOnlyWhateverTheUmask) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  const mode_t old = ::umask(0);  // the most permissive umask
  {
    Gallery g(path, creating());
    g.add_user();  // a write creates the -wal and -shm files
    EXPECT_EQ(file_mode(path), 0600);
    EXPECT_EQ(file_mode(path + "-wal"), 0600);
    EXPECT_EQ(file_mode(path + "-shm"), 0600);
    EXPECT_EQ(g.integrity_check(), "ok");
  }
  ::umask(old);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(s, 0), kGallerySchemaVersion);
  sqlite3_finalize(s);
  sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "wal");
  sqlite3_finalize(s);
  sqlite3_close(db);
}

TEST(Gallery, BadFilesAreOneLineInputErrorsNamingTheFile) {
  TempDir dir;
  const std::string missing = (dir / "missing.db").string();
  EXPECT_EQ(input_error([&] { Gallery g(missing); }), missing + ": gallery not found");
  EXPECT_FALSE(std::filesystem::exists(missing));  // never created silently

  const std::string text = (dir / "notes.db").string();
  bodyrec::testing::write_text(text, std::string(4096, 'x'));
  const std::string e1 = input_error([&] { Gallery g(text); });
  EXPECT_TRUE(contains(e1, text + ": not an SQLite database")) << e1;

  const std::string empty = (dir / "empty.db").string();
  bodyrec::testing::write_text(empty, "");
  EXPECT_EQ(input_error([&] { Gallery g(empty); }), empty + ": empty file, not a bodyrec gallery");

  const std::string other = (dir / "other.db").string();
  raw_exec(other, "CREATE TABLE t(x)");
  EXPECT_EQ(input_error([&] { Gallery g(other, creating()); }),
            other + ": an SQLite database, but not a bodyrec gallery");

  for (const std::string& m : {e1}) EXPECT_EQ(m.find('\n'), std::string::npos);
}

TEST(FeatureBlob, RoundTripsAnyMatrixAndRejectsCorruptBlobs) {
  cv::Mat kaze(3, 64, CV_32F);
  cv::randu(kaze, -1, 1);
  const cv::Mat back = store::decode_features(store::encode_features(kaze), "x");
  EXPECT_EQ(back.type(), CV_32F);
  EXPECT_EQ(cv::norm(back, kaze, cv::NORM_INF), 0.0);
  const cv::Mat bytes = (cv::Mat_<uint8_t>(1, 3) << 1, 2, 3);
  EXPECT_EQ(store::decode_features(store::encode_features(bytes), "x").at<uint8_t>(0, 2), 3);
  auto blob = store::encode_features(kaze);
  blob.pop_back();
  EXPECT_EQ(input_error([&] { store::decode_features(blob, "g.db: user 1"); }),
            "g.db: user 1: corrupt features blob (767 bytes for 3x64)");
  EXPECT_TRUE(contains(input_error([&] { store::decode_features(std::vector<unsigned char>(5), "g"); }),
                       "no BRF1 header"));
}

TEST(GalleryTime, DurationsAndUtcFormat) {
  EXPECT_EQ(parse_duration("30d"), std::chrono::seconds(30 * 86400));
  EXPECT_EQ(parse_duration("12h"), std::chrono::seconds(12 * 3600));
  EXPECT_EQ(parse_duration("45m"), std::chrono::seconds(45 * 60));
  EXPECT_EQ(parse_duration("2w"), std::chrono::seconds(14 * 86400));
  EXPECT_EQ(parse_duration("0s"), std::chrono::seconds(0));
  for (const char* bad : {"", "d", "30", "30x", "-1d", "1.5d", "d30"}) EXPECT_FALSE(parse_duration(bad)) << bad;
  EXPECT_EQ(format_utc(from_unix_ms(0)), "1970-01-01T00:00:00Z");
  EXPECT_EQ(format_utc(from_unix_ms(1795957200000LL)), "2026-11-29T13:00:00Z");
}

}  // namespace
}  // namespace bodyrec
