// The SQLite side of store/connection.h: one connection to a gallery file, prepared statements over
// SQLite's C API.
#pragma once

#include "bodyrec/store/connection.h"

struct sqlite3;

namespace bodyrec::sql {

// Errors throw ProcessingError("<path>: <what>: <sqlite message>"), except SQLITE_NOTADB ("<path>: not an
// SQLite database") and SQLITE_CORRUPT, which throw InputError: a file that is not a database is bad input.
class SqliteConnection : public Connection {
 public:
  // REQUIRES: `flags` are sqlite3_open_v2 flags (SQLITE_OPEN_READONLY or READWRITE[|CREATE]).
  // InputError when the file cannot be opened.
  SqliteConnection(const std::string& path, int flags);
  ~SqliteConnection() override;

  Dialect dialect() const override { return Dialect::kSqlite; }
  void exec(const std::string& sql) override;
  std::unique_ptr<Cursor> prepare(const std::string& sql) override;
  void rollback_quietly() noexcept override;

  // Throws for rc other than SQLITE_OK/ROW/DONE, naming `what`.
  void check(int rc, const char* what) const;
  [[noreturn]] void fail(int rc, const char* what) const;
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace bodyrec::sql
