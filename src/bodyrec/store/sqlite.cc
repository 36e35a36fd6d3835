#include "bodyrec/store/sqlite.h"

#include <sqlite3.h>

#include "bodyrec/core/error.h"

namespace bodyrec::sql {

namespace {

class SqliteCursor : public Cursor {
 public:
  SqliteCursor(SqliteConnection& db, const std::string& sql) : db_(db) {
    db_.check(sqlite3_prepare_v2(db_.handle(), sql.c_str(), -1, &stmt_, nullptr), sql.c_str());
  }
  ~SqliteCursor() override { sqlite3_finalize(stmt_); }

  void bind_int(int index, int64_t value) override { db_.check(sqlite3_bind_int64(stmt_, index, value), "bind"); }
  void bind_double(int index, double value) override { db_.check(sqlite3_bind_double(stmt_, index, value), "bind"); }
  void bind_text(int index, const std::string& value) override {
    db_.check(sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT),
              "bind");
  }
  void bind_blob(int index, const unsigned char* data, size_t size) override {
    db_.check(sqlite3_bind_blob(stmt_, index, data, static_cast<int>(size), SQLITE_TRANSIENT), "bind");
  }
  void bind_null(int index) override { db_.check(sqlite3_bind_null(stmt_, index), "bind"); }

  bool step() override {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) {
      changes_ = sqlite3_changes(db_.handle());
      return false;
    }
    const std::string sql = sqlite3_sql(stmt_);
    sqlite3_reset(stmt_);
    db_.fail(rc, sql.c_str());
  }
  void reset() override {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  int64_t changes() const override { return changes_; }

  bool is_null(int column) const override { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }
  int64_t column_int(int column) const override { return sqlite3_column_int64(stmt_, column); }
  double column_double(int column) const override { return sqlite3_column_double(stmt_, column); }
  std::string column_text(int column) const override {
    const auto* text = sqlite3_column_text(stmt_, column);
    return text ? std::string(reinterpret_cast<const char*>(text), sqlite3_column_bytes(stmt_, column)) : "";
  }
  const unsigned char* column_blob_data(int column) const override {
    return static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, column));
  }
  size_t column_bytes(int column) const override { return static_cast<size_t>(sqlite3_column_bytes(stmt_, column)); }

 private:
  SqliteConnection& db_;
  sqlite3_stmt* stmt_ = nullptr;
  int64_t changes_ = 0;
};

}  // namespace

SqliteConnection::SqliteConnection(const std::string& path, int flags) : Connection(path) {
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close_v2(db_);
    db_ = nullptr;
    if (rc == SQLITE_CANTOPEN || rc == SQLITE_NOTADB || rc == SQLITE_PERM)
      throw InputError(path + ": cannot open gallery: " + message);
    throw ProcessingError(path + ": cannot open gallery: " + message);
  }
  sqlite3_extended_result_codes(db_, 1);
}

SqliteConnection::~SqliteConnection() { sqlite3_close_v2(db_); }

void SqliteConnection::fail(int rc, const char* what) const {
  const int primary = rc & 0xff;
  if (primary == SQLITE_NOTADB) throw InputError(where() + ": not an SQLite database (" + what + ")");
  if (primary == SQLITE_CORRUPT) throw InputError(where() + ": corrupt database: " + sqlite3_errmsg(db_));
  throw ProcessingError(where() + ": " + what + ": " + sqlite3_errmsg(db_));
}

void SqliteConnection::check(int rc, const char* what) const {
  if (rc != SQLITE_OK && rc != SQLITE_ROW && rc != SQLITE_DONE) fail(rc, what);
}

void SqliteConnection::exec(const std::string& sql) {
  check(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), sql.c_str());
}

std::unique_ptr<Cursor> SqliteConnection::prepare(const std::string& sql) {
  return std::make_unique<SqliteCursor>(*this, sql);
}

void SqliteConnection::rollback_quietly() noexcept {
  if (sqlite3_get_autocommit(db_) == 0) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

}  // namespace bodyrec::sql
