// A thin RAII layer over SQLite's C API for the gallery: one connection, prepared statements with bound
// values (never SQL built from values), and transactions that roll back unless committed. No ORM: the
// gallery's SQL stays readable in gallery.cc and schema.cc.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace bodyrec::sql {

// The connection. `where` (the file name) prefixes every error message. Errors throw
// ProcessingError("<where>: <what>: <sqlite message>"), except SQLITE_NOTADB which throws InputError
// ("<where>: not an SQLite database"): a file that is not a database is bad input.
class Database {
 public:
  // REQUIRES: `flags` are sqlite3_open_v2 flags (SQLITE_OPEN_READONLY or READWRITE[|CREATE]).
  Database(const std::string& path, int flags);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs SQL without values (pragmas, DDL); every statement of `sql` is run.
  void exec(const char* sql);
  // One integer from a pragma or query without values, e.g. "PRAGMA user_version".
  int64_t query_int(const char* sql);
  // Throws for rc != SQLITE_OK/ROW/DONE, naming `what`.
  void check(int rc, const char* what) const;
  [[noreturn]] void fail(int rc, const char* what) const;

  int64_t last_insert_rowid() const;
  int changes() const;
  bool in_transaction() const;
  sqlite3* handle() const { return db_; }
  const std::string& where() const { return where_; }

 private:
  sqlite3* db_ = nullptr;
  std::string where_;
};

// A prepared statement; bind values by 1-based index, step, read columns by 0-based index.
class Statement {
 public:
  Statement(Database& db, const char* sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, int64_t value);
  Statement& bind(int index, double value);
  Statement& bind(int index, const std::string& value);
  Statement& bind_blob(int index, const std::vector<unsigned char>& value);  // empty -> NULL
  Statement& bind_null(int index);
  template <typename T>
  Statement& bind(int index, const std::optional<T>& value) {
    return value ? bind(index, *value) : bind_null(index);
  }

  // true while a row is available; false when done.
  bool step();
  // Runs a statement that returns no rows, then resets it for reuse.
  void run();
  void reset();

  bool is_null(int column) const;
  int64_t column_int(int column) const;
  double column_double(int column) const;
  std::string column_text(int column) const;
  std::vector<unsigned char> column_blob(int column) const;
  // Pointer valid until the next step/reset (no copy).
  const unsigned char* column_blob_data(int column) const;
  int column_bytes(int column) const;

 private:
  Database& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE (takes the write lock at once, so two writers queue on the busy timeout instead of
// deadlocking on a lock upgrade) ... COMMIT; rolls back in the destructor unless commit() was called.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace bodyrec::sql
