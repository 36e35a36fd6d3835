#include "bodyrec/store/postgres.h"

#include <libpq-fe.h>

#include <cstdlib>
#include <cstring>

#include "bodyrec/core/error.h"

namespace bodyrec::sql {

namespace {

// Type OIDs of the PostgreSQL catalogue (pg_type.dat; stable across versions).
constexpr Oid kBool = 16, kBytea = 17, kInt8 = 20, kInt2 = 21, kInt4 = 23, kText = 25, kFloat4 = 700, kFloat8 = 701;

// One line: libpq messages end with a newline and may hold several lines (DETAIL, HINT).
std::string one_line(const char* text) {
  std::string s = text ? text : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (char& c : s)
    if (c == '\n' || c == '\t') c = ' ';
  return s;
}

void put_be(std::string& out, uint64_t v, int bytes) {
  out.resize(static_cast<size_t>(bytes));
  for (int i = bytes - 1; i >= 0; --i, v >>= 8) out[static_cast<size_t>(i)] = static_cast<char>(v & 0xff);
}

uint64_t get_be(const char* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

void notice_receiver(void* arg, const PGresult* result) {
  const char* severity = PQresultErrorField(result, PG_DIAG_SEVERITY_NONLOCALIZED);
  if (severity && std::strcmp(severity, "WARNING") == 0)
    static_cast<std::vector<std::string>*>(arg)->push_back(
        one_line(PQresultErrorField(result, PG_DIAG_MESSAGE_PRIMARY)));
}

class PgCursor : public Cursor {
 public:
  PgCursor(PgConnection& db, const std::string& sql) : db_(db), sql_(postgres_placeholders(sql)) {}
  ~PgCursor() override { PQclear(result_); }

  void bind_int(int index, int64_t value) override {
    Param& p = at(index);
    p = {kInt8, {}, false};
    put_be(p.bytes, static_cast<uint64_t>(value), 8);
  }
  void bind_double(int index, double value) override {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    Param& p = at(index);
    p = {kFloat8, {}, false};
    put_be(p.bytes, bits, 8);
  }
  void bind_text(int index, const std::string& value) override { at(index) = {kText, value, false}; }
  void bind_blob(int index, const unsigned char* data, size_t size) override {
    at(index) = {kBytea, std::string(reinterpret_cast<const char*>(data), size), false};
  }
  void bind_null(int index) override { at(index) = {0, {}, true}; }

  bool step() override {
    if (!result_) {
      execute();
    } else if (row_ < rows_) {
      ++row_;
    }
    return row_ < rows_;
  }
  void reset() override {
    PQclear(result_);
    result_ = nullptr;
    params_.clear();
    row_ = rows_ = 0;
  }
  int64_t changes() const override { return changes_; }

  bool is_null(int column) const override { return PQgetisnull(result_, row_, column) != 0; }
  int64_t column_int(int column) const override {
    if (is_null(column)) return 0;
    const char* v = PQgetvalue(result_, row_, column);
    switch (PQftype(result_, column)) {
      case kInt8: return static_cast<int64_t>(get_be(v, 8));
      case kInt4: return static_cast<int32_t>(get_be(v, 4));
      case kInt2: return static_cast<int16_t>(get_be(v, 2));
      case kBool: return v[0] != 0;
      default: return static_cast<int64_t>(column_double(column));
    }
  }
  double column_double(int column) const override {
    if (is_null(column)) return 0;
    const char* v = PQgetvalue(result_, row_, column);
    const Oid type = PQftype(result_, column);
    if (type == kFloat8) {
      const uint64_t bits = get_be(v, 8);
      double d = 0;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    if (type == kFloat4) {
      const auto bits = static_cast<uint32_t>(get_be(v, 4));
      float f = 0;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    if (type == kInt8 || type == kInt4 || type == kInt2 || type == kBool) return static_cast<double>(column_int(column));
    throw ProcessingError(db_.where() + ": column " + std::to_string(column) + " of " + sql_ +
                          ": unexpected type oid " + std::to_string(type));
  }
  std::string column_text(int column) const override {
    if (is_null(column)) return "";
    return std::string(PQgetvalue(result_, row_, column), static_cast<size_t>(PQgetlength(result_, row_, column)));
  }
  const unsigned char* column_blob_data(int column) const override {
    if (is_null(column)) return nullptr;
    return reinterpret_cast<const unsigned char*>(PQgetvalue(result_, row_, column));
  }
  size_t column_bytes(int column) const override {
    return static_cast<size_t>(PQgetlength(result_, row_, column));
  }

 private:
  struct Param {
    Oid type = 0;
    std::string bytes;
    bool null = true;
  };
  Param& at(int index) {
    if (index < 1) throw ProcessingError(db_.where() + ": bind index " + std::to_string(index) + " of " + sql_);
    if (static_cast<size_t>(index) > params_.size()) params_.resize(static_cast<size_t>(index));
    return params_[static_cast<size_t>(index) - 1];
  }
  void execute() {
    const int n = static_cast<int>(params_.size());
    std::vector<Oid> types(params_.size());
    std::vector<const char*> values(params_.size());
    std::vector<int> lengths(params_.size()), formats(params_.size(), 1);
    for (size_t i = 0; i < params_.size(); ++i) {
      types[i] = params_[i].type;
      values[i] = params_[i].null ? nullptr : params_[i].bytes.data();
      lengths[i] = static_cast<int>(params_[i].bytes.size());
    }
    PGresult* r = PQexecParams(db_.handle(), sql_.c_str(), n, types.data(), values.data(), lengths.data(),
                               formats.data(), 1);
    const ExecStatusType status = PQresultStatus(r);
    if (status != PGRES_TUPLES_OK && status != PGRES_COMMAND_OK) db_.fail(r, sql_);
    result_ = r;
    rows_ = PQntuples(r);
    row_ = 0;
    const char* affected = PQcmdTuples(r);
    changes_ = (affected && *affected) ? std::atoll(affected) : 0;
  }

  PgConnection& db_;
  std::string sql_;
  std::vector<Param> params_;
  PGresult* result_ = nullptr;
  int row_ = 0, rows_ = 0;
  int64_t changes_ = 0;
};

}  // namespace

bool is_postgres_uri(const std::string& location) {
  return location.rfind("postgresql://", 0) == 0 || location.rfind("postgres://", 0) == 0;
}

void check_postgres_uri(const std::string& uri) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(uri.c_str(), &error);
  if (!options) {
    const std::string message = error ? one_line(error) : "out of memory";
    PQfreemem(error);
    throw UsageError("--gallery: not a valid PostgreSQL connection URI: " + message);
  }
  bool password = false;
  for (const PQconninfoOption* o = options; o->keyword; ++o)
    if (std::strcmp(o->keyword, "password") == 0 && o->val && *o->val) password = true;
  PQconninfoFree(options);
  if (password)
    throw UsageError(
        "--gallery: the PostgreSQL URI holds a password; the command line is visible to every user of the machine. "
        "Put the password in a password file (PGPASSFILE or ~/.pgpass, mode 0600) or a service file (PGSERVICEFILE) "
        "and leave it out of the URI");
}

PgConnection::PgConnection(const std::string& uri) : Connection(uri) {
  check_postgres_uri(uri);
  conn_ = PQconnectdb(uri.c_str());
  if (!conn_) throw ProcessingError(uri + ": cannot connect: out of memory");
  if (PQstatus(conn_) != CONNECTION_OK) {
    const std::string message = one_line(PQerrorMessage(conn_));
    PQfinish(conn_);
    conn_ = nullptr;
    throw InputError(uri + ": cannot connect: " + message);
  }
  PQsetNoticeReceiver(conn_, notice_receiver, &warnings_);
}

PgConnection::~PgConnection() { PQfinish(conn_); }

void PgConnection::fail(void* result, const std::string& what) const {
  auto* r = static_cast<PGresult*>(result);
  const char* primary = r ? PQresultErrorField(r, PG_DIAG_MESSAGE_PRIMARY) : nullptr;
  const std::string message = one_line(primary ? primary : PQerrorMessage(conn_));
  PQclear(r);
  if (PQstatus(conn_) == CONNECTION_BAD)
    throw ProcessingError(where() + ": lost the connection to the PostgreSQL server (" + message +
                          "); nothing after the last committed write was stored");
  throw ProcessingError(where() + ": " + one_line(what.c_str()) + ": " + message);
}

void PgConnection::exec(const std::string& sql) {
  PGresult* r = PQexec(conn_, sql.c_str());
  const ExecStatusType status = PQresultStatus(r);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK && status != PGRES_EMPTY_QUERY) fail(r, sql);
  PQclear(r);
}

std::unique_ptr<Cursor> PgConnection::prepare(const std::string& sql) { return std::make_unique<PgCursor>(*this, sql); }

void PgConnection::rollback_quietly() noexcept {
  if (!conn_ || PQstatus(conn_) != CONNECTION_OK) return;
  const PGTransactionStatusType t = PQtransactionStatus(conn_);
  if (t == PQTRANS_INTRANS || t == PQTRANS_INERROR) PQclear(PQexec(conn_, "ROLLBACK"));
}

std::vector<std::string> PgConnection::take_warnings() {
  std::vector<std::string> out;
  out.swap(warnings_);
  return out;
}

std::string postgres_placeholders(const std::string& sql) {
  std::string out;
  out.reserve(sql.size());
  char quote = 0;  // ' or " while inside a string or quoted identifier
  bool comment = false;
  for (size_t i = 0; i < sql.size(); ++i) {
    const char c = sql[i];
    if (comment) {
      comment = c != '\n';
    } else if (quote) {
      if (c == quote) quote = 0;  // a doubled quote closes and reopens: same result
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '-' && i + 1 < sql.size() && sql[i + 1] == '-') {
      comment = true;
    } else if (c == '?' && i + 1 < sql.size() && sql[i + 1] >= '0' && sql[i + 1] <= '9') {
      out += '$';
      continue;
    }
    out += c;
  }
  return out;
}

}  // namespace bodyrec::sql
