#include "bodyrec/io/json_numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace bodyrec {
namespace {

void round_in_place(nlohmann::json& value, int digits) {
  if (value.is_number_float()) {
    value = round_significant(value.get<double>(), digits);
  } else if (value.is_structured()) {
    for (auto& item : value) round_in_place(item, digits);
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

std::string json_text(const nlohmann::json& value) { return round_numbers(value).dump(); }

}  // namespace bodyrec
