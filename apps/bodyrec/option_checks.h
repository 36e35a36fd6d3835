// Option values checked with messages a person can read, and CLI11's parse errors turned into bodyrec's
// one-line format. The validators below replace CLI11's PositiveNumber, NonNegativeNumber, Range and
// IsMember, whose messages print the bound as a 300-digit number ("Value 0 not in range 0.000000 to
// 1797693...") and let NaN through (every comparison with NaN is false).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace bodyrec::cli {

// "--every: 0 is not a positive number"; NaN, infinities and text that is not a number are refused too.
CLI::Validator positive();
// "--min-visible: -1 is not a non-negative number".
CLI::Validator non_negative();
// "--min-visible: 1.5 is not in [0, 1]" (bounds included).
CLI::Validator in_range(double low, double high);
// "--preset: 'fast' is not one of default, thesis".
CLI::Validator one_of(std::vector<std::string> choices);

// Adds to every option of `app` and of its subcommands, at any depth, that takes numbers (type FLOAT,
// INT or UINT) a check that each value is one: "--hit-threshold: nan is not a finite number",
// "--every: 2.5 is not a whole number", "--scale: fast is not a number". Call it once the whole command
// tree is built, before parsing.
void check_numbers_everywhere(CLI::App& app);

// Options of `app` and its subcommands whose default is an empty list (repeatable or several values, such
// as --eval or --roi) show no default in --help: CLI11 would print "=[]".
void hide_empty_list_defaults_everywhere(CLI::App& app);

// `text` on one line: newlines, carriage returns and tabs become spaces, trailing spaces go.
std::string one_line(std::string text);

// One line for a CLI11 parse error (without the "bodyrec: error: " prefix): the option and the value at
// fault in plain words. `app` is the root, parsed (or partly parsed) when `error` was thrown: an unknown
// or missing command is named with the level it is missing at ("bodyrec eval").
std::string usage_message(const CLI::ParseError& error, const CLI::App& app);

}  // namespace bodyrec::cli
