#include "bodyrec/io/json_numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace bodyrec {
namespace {

void round_in_place(nlohmann::json& value, int digits) {
  if (value.is_number_float()) {
    value = round_significant(value.get<double>(), digits);
  } else if (value.is_structured()) {
    for (auto& item : value) round_in_place(item, digits);
  }
}

// The shortest text that reads back as `v`, laid out as nlohmann::json lays out numbers (decimal notation for
// exponents -4..15, "1.0" for whole numbers, else "1.5e+20"). nlohmann's own Grisu2 is not always shortest:
// 8.73529 comes out as 8.735290000000001.
std::string number_text(double v) {
  if (!std::isfinite(v)) return "null";  // as nlohmann writes them
  if (v == 0) return std::signbit(v) ? "-0.0" : "0.0";
  char text[64];
  int precision = 1;
  for (; precision < 17; ++precision) {
    std::snprintf(text, sizeof text, "%.*e", precision - 1, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  std::snprintf(text, sizeof text, "%.*e", precision - 1, v);
  // text: [-]d[.ddd]e[+-]xx -> its digits and where the decimal point goes.
  std::string s(text), digits;
  const bool negative = s[0] == '-';
  const size_t e = s.find('e');
  for (size_t i = negative ? 1 : 0; i < e; ++i)
    if (s[i] != '.') digits += s[i];
  const int k = static_cast<int>(digits.size());
  const int n = std::atoi(s.c_str() + e + 1) + 1;  // the point after n digits
  std::string out = negative ? "-" : "";
  if (k <= n && n <= 15) {
    out += digits + std::string(static_cast<size_t>(n - k), '0') + ".0";
  } else if (0 < n && n <= 15) {
    out += digits.substr(0, static_cast<size_t>(n)) + "." + digits.substr(static_cast<size_t>(n));
  } else if (-4 < n && n <= 0) {
    out += "0." + std::string(static_cast<size_t>(-n), '0') + digits;
  } else {
    out += digits.substr(0, 1) + (k > 1 ? "." + digits.substr(1) : "");
    const int exponent = n - 1;
    char tail[16];
    std::snprintf(tail, sizeof tail, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
    out += tail;
  }
  return out;
}

void write_json(const nlohmann::json& value, int digits, std::string& out) {
  if (value.is_object()) {
    out += '{';
    bool first = true;
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (!first) out += ',';
      first = false;
      out += nlohmann::json(it.key()).dump();
      out += ':';
      write_json(it.value(), digits, out);
    }
    out += '}';
  } else if (value.is_array()) {
    out += '[';
    for (size_t i = 0; i < value.size(); ++i) {
      if (i > 0) out += ',';
      write_json(value[i], digits, out);
    }
    out += ']';
  } else if (value.is_number_float()) {
    out += number_text(round_significant(value.get<double>(), digits));
  } else {
    out += value.dump();
  }
}

}  // namespace

double round_significant(double v, int digits) {
  if (!std::isfinite(v) || v == 0) return v;
  const double magnitude = std::fabs(v);
  const int integer_digits = magnitude >= 1 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
  // Numbers with `digits` integer digits or more keep three decimals: Unix times in seconds carry
  // milliseconds (latency is read from them).
  const int keep = std::clamp(integer_digits >= digits ? integer_digits + 3 : digits, 1, 17);
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", keep, v);
  return std::strtod(text, nullptr);
}

nlohmann::json round_numbers(const nlohmann::json& value, int digits) {
  nlohmann::json copy = value;
  round_in_place(copy, digits);
  return copy;
}

std::string json_text(const nlohmann::json& value) {
  std::string out;
  write_json(value, kJsonDigits, out);
  return out;
}

}  // namespace bodyrec
