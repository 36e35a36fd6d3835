// The small database interface the gallery is written against (issue 47): prepare / bind / step /
// column, statements without values, and rollback. Two implementations: SQLite (sqlite.h, the
// embedded default) and PostgreSQL through libpq (postgres.h, one gallery shared by a site's sensors).
//
// Why this interface and not two galleries: the gallery's SQL and logic (best scan per view, event
// caps, erasure, the feature cache) stay one piece of code, tested once against both databases. What
// differs lives in two places only: the connections here (placeholders, value encoding, error
// classes) and store/gallery_backend.h (column types, identity columns, pragmas and their PostgreSQL
// counterparts, write locking, change detection, scrubbing after erasure).
//
// SQL is written once, in the dialect both databases accept: numbered placeholders `?1`, `?2` (the
// PostgreSQL connection rewrites them to `$1`, `$2`), `"user"` quoted (a reserved word in PostgreSQL),
// `INSERT ... RETURNING id` instead of last_insert_rowid(), CASE instead of the two-argument
// max()/min() SQLite has and PostgreSQL calls GREATEST/LEAST.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyrec::sql {

enum class Dialect { kSqlite, kPostgres };

// One statement's backend side. Bind by 1-based index, read columns by 0-based index.
class Cursor {
 public:
  virtual ~Cursor() = default;
  virtual void bind_int(int index, int64_t value) = 0;
  virtual void bind_double(int index, double value) = 0;
  virtual void bind_text(int index, const std::string& value) = 0;
  virtual void bind_blob(int index, const unsigned char* data, size_t size) = 0;
  virtual void bind_null(int index) = 0;
  virtual bool step() = 0;   // true while a row is available
  virtual void reset() = 0;  // ready to run again; bindings cleared
  virtual int64_t changes() const = 0;  // rows the last run inserted, updated or deleted
  virtual bool is_null(int column) const = 0;
  virtual int64_t column_int(int column) const = 0;
  virtual double column_double(int column) const = 0;
  virtual std::string column_text(int column) const = 0;
  // Valid until the next step/reset (no copy).
  virtual const unsigned char* column_blob_data(int column) const = 0;
  virtual size_t column_bytes(int column) const = 0;
};

// A connection. `where` (the file name or connection URI) prefixes every error message. Errors throw
// ProcessingError("<where>: <what>: <database message>"); a file or server that is not a usable
// database at all throws InputError.
class Connection {
 public:
  explicit Connection(std::string where) : where_(std::move(where)) {}
  virtual ~Connection() = default;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  virtual Dialect dialect() const = 0;
  // Runs SQL without values (DDL, transaction control, settings); every statement of `sql` is run.
  virtual void exec(const std::string& sql) = 0;
  virtual std::unique_ptr<Cursor> prepare(const std::string& sql) = 0;
  // Rolls back the open transaction, if any, and never throws (error paths, destructors).
  virtual void rollback_quietly() noexcept = 0;

  // The first column of the first row of a query without values (0 when there is no row).
  int64_t query_int(const std::string& sql);
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

// A prepared statement with the values bound to it (never SQL built from values).
class Statement {
 public:
  Statement(Connection& db, const std::string& sql) : cursor_(db.prepare(sql)) {}

  Statement& bind(int index, int64_t value) { return cursor_->bind_int(index, value), *this; }
  Statement& bind(int index, double value) { return cursor_->bind_double(index, value), *this; }
  Statement& bind(int index, const std::string& value) { return cursor_->bind_text(index, value), *this; }
  Statement& bind_blob(int index, const std::vector<unsigned char>& value);  // empty -> NULL
  Statement& bind_null(int index) { return cursor_->bind_null(index), *this; }
  template <typename T>
  Statement& bind(int index, const std::optional<T>& value) {
    return value ? bind(index, *value) : bind_null(index);
  }

  bool step() { return cursor_->step(); }
  // Runs a statement that returns no rows, then resets it for reuse.
  void run();
  void reset() { cursor_->reset(); }
  int64_t changes() const { return cursor_->changes(); }

  bool is_null(int column) const { return cursor_->is_null(column); }
  int64_t column_int(int column) const { return cursor_->column_int(column); }
  double column_double(int column) const { return cursor_->column_double(column); }
  std::string column_text(int column) const { return cursor_->column_text(column); }
  std::vector<unsigned char> column_blob(int column) const;
  const unsigned char* column_blob_data(int column) const { return cursor_->column_blob_data(column); }
  size_t column_bytes(int column) const { return cursor_->column_bytes(column); }

 private:
  std::unique_ptr<Cursor> cursor_;
};

}  // namespace bodyrec::sql
