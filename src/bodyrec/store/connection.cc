#include "bodyrec/store/connection.h"

namespace bodyrec::sql {

int64_t Connection::query_int(const std::string& sql) {
  Statement s(*this, sql);
  return s.step() ? s.column_int(0) : 0;
}

Statement& Statement::bind_blob(int index, const std::vector<unsigned char>& value) {
  if (value.empty()) return bind_null(index);
  cursor_->bind_blob(index, value.data(), value.size());
  return *this;
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

std::vector<unsigned char> Statement::column_blob(int column) const {
  const unsigned char* data = column_blob_data(column);
  return data ? std::vector<unsigned char>(data, data + column_bytes(column)) : std::vector<unsigned char>();
}

}  // namespace bodyrec::sql
