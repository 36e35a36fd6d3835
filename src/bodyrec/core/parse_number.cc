#include "bodyrec/core/parse_number.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<double> parse_double(std::string_view token) {
  const std::string text(trim(token));  // strtod needs a terminated string
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return v;
}

std::optional<long long> parse_integer(std::string_view token) {
  const std::string text(trim(token));
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return v;
}

double parse_finite_field(const std::string& text, const std::string& where, const char* field) {
  const auto v = parse_double(text);
  if (!v || !std::isfinite(*v))
    throw InputError(where + ": field '" + field + "' is not a finite number: '" + text + "'");
  return *v;
}

}  // namespace bodyrec
