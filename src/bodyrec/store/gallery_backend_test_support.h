// The gallery suite runs against both databases (issue 47): GalleryBackendTest's parameter says which.
// gallery_suite_test.cc holds the tests; store_test instantiates them with SQLite (gallery_test.cc),
// store_server_test with PostgreSQL on a private server (gallery_server_test.cc, ctest label `server`).
#pragma once

#include <sqlite3.h>

#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/store/connection.h"
#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_test_support.h"
#include "server_fixtures.h"
#include "test_support.h"

namespace bodyrec::sql {
inline void PrintTo(Dialect dialect, std::ostream* os) { *os << (dialect == Dialect::kPostgres ? "PostgreSQL" : "SQLite"); }
}  // namespace bodyrec::sql

namespace bodyrec::store::testing {

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Privacy tests: 24 bytes from the middle of the scan's PNG encoding (random pixels: unique to this image), and 24
// bytes of its feature blob's data.
struct Patterns {
  std::string image, features;
};

inline Patterns patterns_of(const GalleryScan& scan) {
  std::vector<unsigned char> png;
  cv::imencode(".png", scan.image, png);
  const auto blob = store::encode_features(scan.features);
  const auto middle = png.begin() + static_cast<long>(png.size() / 2);
  return {std::string(middle, middle + 24), std::string(blob.begin() + 16, blob.begin() + 40)};
}

inline GalleryScan distinct_scan(int seed) {
  GalleryScan scan = make_scan(View::F, 0.5, seed, 96, 48);
  cv::RNG rng(static_cast<uint64_t>(seed) + 99);
  rng.fill(scan.features, cv::RNG::UNIFORM, 0.0, 1.0);
  return scan;
}

// A fresh gallery per call on one database (dialect_), with raw access to what it stored.
class GalleryDbFixture : public ::testing::Test {
 protected:
  explicit GalleryDbFixture(sql::Dialect dialect = sql::Dialect::kSqlite) : dialect_(dialect) {}
  void SetUp() override {
    if (postgres()) {
      BODYREC_REQUIRE_POSTGRES(pg);
      pg_ = pg;
    }
  }
  bool postgres() const { return dialect_ == sql::Dialect::kPostgres; }

  // A new, empty gallery location: a file name in the test's folder, or a new database's URI.
  std::string fresh() {
    if (!postgres()) return (dir_ / ("g" + std::to_string(++count_) + ".db")).string();
    const std::string uri = pg_->create_database("g");
    databases_[uri] = uri.substr(uri.find("///") + 3, uri.find('?') - uri.find("///") - 3);
    return uri;
  }
  // SQL straight on the database, bypassing the gallery.
  void raw_sql(const std::string& location, const std::string& sql) {
    if (postgres()) return pg_->exec(databases_.at(location), sql);
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(location.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    sqlite3_close(db);
  }
  void set_schema_version(const std::string& location, int version) {
    raw_sql(location, postgres() ? "UPDATE bodyrec_gallery SET schema_version = " + std::to_string(version)
                                 : "PRAGMA user_version = " + std::to_string(version));
  }
  // Every byte the database keeps on disk for the gallery outside a write-ahead log that a checkpoint
  // empties: SQLite's .db and -wal; PostgreSQL's table files (after a CHECKPOINT), not its WAL.
  std::string stored_bytes(const std::string& location) {
    if (!postgres()) return file_bytes(location) + file_bytes(location + "-wal");
    pg_->exec("postgres", "CHECKPOINT");
    return pg_->table_files_bytes(databases_.at(location));
  }
  static GalleryOptions creating() {
    GalleryOptions o;
    o.create = true;
    return o;
  }

  sql::Dialect dialect_;
  bodyrec::testing::TempDir dir_;
  bodyrec::testing::PostgresServer* pg_ = nullptr;
  std::map<std::string, std::string> databases_;  // URI -> database name
  int count_ = 0;
};

class GalleryBackendTest : public GalleryDbFixture, public ::testing::WithParamInterface<sql::Dialect> {
 protected:
  GalleryBackendTest() : GalleryDbFixture(GetParam()) {}
};

inline std::string backend_name(const ::testing::TestParamInfo<sql::Dialect>& info) {
  return info.param == sql::Dialect::kPostgres ? "postgresql" : "sqlite";
}

// The suites (one fixture, three names): gallery_suite_test.cc, privacy_suite_test.cc,
// crash_safety_suite_test.cc.
class GallerySuite : public GalleryBackendTest {};
class GalleryPrivacy : public GalleryBackendTest {};
class GalleryCrashSafety : public GalleryBackendTest {};

}  // namespace bodyrec::store::testing

// Instantiates every suite above for one database (`dialect`: sql::Dialect::kSqlite or kPostgres).
#define BODYREC_INSTANTIATE_GALLERY_SUITES(dialect)                                                             \
  INSTANTIATE_TEST_SUITE_P(Db, GallerySuite, ::testing::Values(dialect), ::bodyrec::store::testing::backend_name); \
  INSTANTIATE_TEST_SUITE_P(Db, GalleryPrivacy, ::testing::Values(dialect), ::bodyrec::store::testing::backend_name); \
  INSTANTIATE_TEST_SUITE_P(Db, GalleryCrashSafety, ::testing::Values(dialect), ::bodyrec::store::testing::backend_name)

namespace bodyrec::store::testing {

}  // namespace bodyrec::store::testing
