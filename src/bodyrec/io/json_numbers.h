// JSON numbers written with the precision they carry. A double computed as 0.1 * 0.7857 prints as
// 0.07856999999999999 (the shortest text that reads back to the same double); no measurement bodyrec
// writes has 16 significant digits, so every JSON output (JSONL lines, --json summaries) rounds its
// floating-point numbers to kJsonDigits significant digits first. Integers are untouched, and a number's
// integer part and three decimals are never rounded away (a Unix time of 1733312345.25 s stays whole).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace bodyrec {

constexpr int kJsonDigits = 6;

// `v` rounded to `digits` significant digits, but never to fewer than its integer digits and three
// decimals; NaN and infinities as they are.
double round_significant(double v, int digits = kJsonDigits);

// A copy of `value` with every floating-point number (at any depth) rounded by round_significant.
nlohmann::json round_numbers(const nlohmann::json& value, int digits = kJsonDigits);

// round_numbers(value).dump(), one line of JSON, except that each number is written as the shortest text
// that reads back to it (nlohmann's dump() sometimes is not: 8.735290000000001 for 8.73529).
std::string json_text(const nlohmann::json& value);

}  // namespace bodyrec
