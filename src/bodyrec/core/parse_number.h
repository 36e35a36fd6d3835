// Whole-token number parsing shared by every text parser (CSV, MOT, XML attributes, obsmat, PCD, NTU,
// homographies, models): a token is a number only if all of it is (spaces and tabs around it allowed).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace bodyrec {

// The value, or nullopt for an empty token or trailing garbage. "nan" and "inf" parse (as strtod reads
// them) and overflow gives +-inf: callers that need finite values check std::isfinite.
std::optional<double> parse_double(std::string_view token);

// The value, or nullopt for an empty token, trailing garbage (including a decimal point) or overflow.
std::optional<long long> parse_integer(std::string_view token);

// A finite number, else InputError "<where>: field '<field>' is not a finite number: '<text>'".
double parse_finite_field(const std::string& text, const std::string& where, const char* field);

}  // namespace bodyrec
