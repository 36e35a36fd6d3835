// Options whose values are names of an enum's members (--roles groups|thesis|voting): parsed from text here,
// at the command line, so the library sees only the enum.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace bodyrec::cli {

// Adds `name` taking one of `choices` (text, value) and storing the value in `target` (an enum, or a
// std::optional of one); anything else is a usage error listing the choices. `default_text` is shown in
// --help.
template <typename Target, typename Enum>
CLI::Option* add_enum_option(CLI::App& sub, const std::string& name, Target& target,
                             std::vector<std::pair<std::string, Enum>> choices, const std::string& help,
                             const std::string& default_text) {
  std::vector<std::string> names;
  std::string type;
  for (const auto& [text, value] : choices) {
    names.push_back(text);
    type += (type.empty() ? "" : "|") + text;
  }
  CLI::Option* option = sub.add_option_function<std::string>(
      name,
      [&target, choices](const std::string& text) {
        for (const auto& [t, value] : choices)
          if (t == text) target = value;
      },
      help);
  option->check(CLI::IsMember(names))->type_name(type)->default_str(default_text);
  return option;
}

}  // namespace bodyrec::cli
