#include "option_checks.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <regex>
#include <sstream>

namespace bodyrec::cli {
namespace {

// The whole of `text` as a double (CLI11 reads numbers the same way: strtod syntax), or nullopt.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  if (errno == ERANGE && std::isinf(v)) return v;  // 1e999: refused below as not finite
  return v;
}

// "" when `text` is a finite number, else why not.
std::string not_a_finite_number(const std::string& text) {
  const auto v = parse_number(text);
  if (!v) return text + " is not a number";
  if (!std::isfinite(*v)) return text + " is not a finite number";
  return "";
}

// Bounds as people write them: 1, 0.05, 100000, 1e+30.
std::string bound(double v) {
  char text[32];
  if (std::fabs(v) < 1e15 && v == std::floor(v))
    std::snprintf(text, sizeof text, "%.0f", v);
  else
    std::snprintf(text, sizeof text, "%g", v);
  return text;
}

CLI::Validator number_check(const std::string& description, const std::string& name,
                            std::function<bool(double)> ok, const std::string& what) {
  return CLI::Validator(
      [ok, what](std::string& text) -> std::string {
        if (const std::string problem = not_a_finite_number(text); !problem.empty()) return problem;
        return ok(*parse_number(text)) ? "" : text + " is not " + what;
      },
      description, name);
}

std::string base_type(const CLI::Option& option) {
  const std::string full = option.get_type_name();
  return full.substr(0, full.find(':'));
}

void add_number_checks(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size_max() == 0) continue;  // a flag
    const std::string type = base_type(*option);
    if (type == "FLOAT") {
      option->check(CLI::Validator(not_a_finite_number, "", "finite"));
    } else if (type == "INT" || type == "UINT") {
      const bool is_unsigned = type == "UINT";
      option->check(CLI::Validator(
          [is_unsigned](std::string& text) -> std::string {
            if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) ||
                (is_unsigned && text.front() == '-'))
              return text + " is not a whole number" + (is_unsigned ? " >= 0" : "");
            char* end = nullptr;
            errno = 0;
            (void)std::strtoll(text.c_str(), &end, 10);
            if (end != text.c_str() + text.size()) {
              const auto v = parse_number(text);
              return text + (v && std::isfinite(*v) ? " is not a whole number" : " is not a number");
            }
            if (errno == ERANGE) return text + " is out of range";
            return "";
          },
          "", "whole"));
    }
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) add_number_checks(*sub);
}

// The deepest command given on the command line ("bodyrec", "bodyrec eval", "bodyrec gallery").
const CLI::App* deepest_parsed(const CLI::App& app) {
  const CLI::App* at = &app;
  for (;;) {
    const auto parsed = at->get_subcommands();
    if (parsed.empty()) return at;
    at = parsed.back();
  }
}

std::string command_path(const CLI::App* app) {
  std::string path;
  for (; app; app = app->get_parent()) path = app->get_name() + (path.empty() ? "" : " " + path);
  return path;
}

std::string subcommand_names(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

std::string plural(long n, const char* one) { return std::to_string(n) + " " + one + (n == 1 ? "" : "s"); }

}  // namespace

CLI::Validator positive() {
  return number_check("POSITIVE", "positive", [](double v) { return v > 0; }, "a positive number");
}

CLI::Validator non_negative() {
  return number_check("NONNEGATIVE", "non-negative", [](double v) { return v >= 0; }, "a non-negative number");
}

CLI::Validator in_range(double low, double high) {
  const std::string range = "[" + bound(low) + ", " + bound(high) + "]";
  return number_check(range, "range", [low, high](double v) { return v >= low && v <= high; }, "in " + range);
}

CLI::Validator one_of(std::vector<std::string> choices) {
  std::string list, braces;
  for (const auto& c : choices) {
    list += (list.empty() ? "" : ", ") + c;
    braces += (braces.empty() ? "" : ",") + c;
  }
  return CLI::Validator(
      [choices, list](std::string& text) -> std::string {
        for (const auto& c : choices)
          if (c == text) return "";
        return "'" + text + "' is not one of " + list;
      },
      "{" + braces + "}", "one of");
}

void check_numbers_everywhere(CLI::App& app) { add_number_checks(app); }

void hide_empty_list_defaults_everywhere(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    if (option->get_default_str() == "[]") option->default_str("");
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) hide_empty_list_defaults_everywhere(*sub);
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  const size_t end = text.find_last_not_of(' ');
  return end == std::string::npos ? text : text.substr(0, end + 1);
}

std::string usage_message(const CLI::ParseError& error, const CLI::App& app) {
  std::string m = one_line(error.what());
  std::smatch g;
  const auto matches = [&](const char* pattern) { return std::regex_match(m, g, std::regex(pattern)); };

  if (dynamic_cast<const CLI::RequiredError*>(&error) && (m == "A subcommand" || m == "A subcommand is required")) {
    const CLI::App* at = deepest_parsed(app);
    auto left = at->remaining();
    if (left.empty()) left = app.remaining(true);  // with fallthrough, a subcommand's stray word lands at the root
    // The line already starts "bodyrec: error: ": name the level only below the root ("eval: ...").
    const std::string where = at->get_parent() ? command_path(at).substr(app.get_name().size() + 1) + ": " : "";
    if (!left.empty())
      return where + "unknown command '" + left.front() + "' (one of " + subcommand_names(*at) + ")";
    return where + "a command is required (one of " + subcommand_names(*at) + ")";
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error) && matches("The following arguments? (?:was|were) not expected: (.*)")) {
    const std::string what = g[1];
    // An unknown option brings its value along as a second extra: name the option (not a negative number).
    std::istringstream words(what);
    for (std::string word; words >> word;)
      if (word.size() > 1 && word[0] == '-' && !std::isdigit(static_cast<unsigned char>(word[1])) && word[1] != '.')
        return "unknown option " + word + " (see " + command_path(deepest_parsed(app)) + " --help)";
    return "unexpected argument" + std::string(what.find(' ') == std::string::npos ? " " : "s ") + what + " (see " +
           command_path(deepest_parsed(app)) + " --help)";
  }
  if (matches(R"((\S+): \d+ required .* missing)")) return std::string(g[1]) + ": missing value";
  if (matches(R"((\S+): At least (\d+) required but received (\d+))"))
    return std::string(g[1]) + ": expects " + plural(std::stol(g[2]), "value") + ", got " + std::string(g[3]);
  if (matches(R"((\S+): At Most (\d+) required but received (\d+))"))
    return std::string(g[1]) + ": expects at most " + plural(std::stol(g[2]), "value") + ", got " + std::string(g[3]);
  if (matches(R"(Expected (exactly|at least) (\d+) arguments to (\S+), got (\d+))"))
    return std::string(g[3]) + ": expects " + (g[1] == "exactly" ? "" : "at least ") + plural(std::stol(g[2]), "value") +
           ", got " + std::string(g[4]);
  if (matches(R"(Could not convert: (\S+) = (.*))"))  // a number the option's type cannot hold, or worse
    return std::string(g[1]) + ": " + std::string(g[2]) +
           (parse_number(g[2]) ? " is out of range" : " is not a valid value");
  if (matches(R"(The value (.*) is not an allowed value for (\S+))"))
    return std::string(g[2]) + ": " + std::string(g[1]) + " is not an allowed value";
  return m;  // ValidationError ("--every: 0 is not a positive number"), "--gt is required", ...
}

}  // namespace bodyrec::cli
