// The PostgreSQL side of store/connection.h, over libpq (Debian libpq-dev): a site's gallery on one
// server, shared by its sensors. Values travel in binary (no quoting, no hex round trip for images);
// `?N` placeholders become `$N`.
#pragma once

#include <string>
#include <vector>

#include "bodyrec/store/connection.h"

struct pg_conn;

namespace bodyrec::sql {

// The connection URI's parts that matter before connecting. `uri` is a libpq connection URI
// (postgresql://... or postgres://...).
bool is_postgres_uri(const std::string& location);
// UsageError when `uri` does not parse, or when it carries a password (in the user info or as
// ?password=): a command line is visible to every user of the machine, so passwords come from a
// password file (PGPASSFILE, ~/.pgpass) or a service file instead. The message never repeats the URI.
void check_postgres_uri(const std::string& uri);

// Errors: InputError("<uri>: cannot connect: <libpq message>") when the server cannot be reached, the
// database does not exist or authentication fails; ProcessingError("<uri>: <what>: <server message>")
// for a failed statement, and ProcessingError("<uri>: lost the connection to the PostgreSQL server
// (...)") when the server went away (restart, network): nothing of the open transaction was committed.
class PgConnection : public Connection {
 public:
  explicit PgConnection(const std::string& uri);  // check_postgres_uri first
  ~PgConnection() override;

  Dialect dialect() const override { return Dialect::kPostgres; }
  void exec(const std::string& sql) override;
  std::unique_ptr<Cursor> prepare(const std::string& sql) override;
  void rollback_quietly() noexcept override;

  // Warnings the server sent since the last call (e.g. VACUUM skipping a table it may not vacuum).
  std::vector<std::string> take_warnings();
  pg_conn* handle() const { return conn_; }
  // Throws the error of a failed result (PGresult*), naming `what`; frees it.
  [[noreturn]] void fail(void* result, const std::string& what) const;

 private:
  pg_conn* conn_ = nullptr;
  std::vector<std::string> warnings_;
};

// `?1` -> `$1` outside quoted strings and identifiers.
std::string postgres_placeholders(const std::string& sql);

}  // namespace bodyrec::sql
