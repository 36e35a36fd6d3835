// How subcommands join the `bodyrec` program: each command file registers a function that adds its
// CLI11 subcommand (options, defaults, help, callback). main() builds the tree from the registry, so a
// new capability adds one file and touches nothing else.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace bodyrec::cli {

struct CommandSpec {
  std::string parent;  // "" for `bodyrec NAME`, "eval" for `bodyrec eval NAME`
  int order = 0;       // position in --help (the pipeline order)
  std::function<void(CLI::App& parent)> add;
};

// Called from a static initialiser in each command file; returns true so it can initialise a constant.
bool register_command(CommandSpec spec);

// The registered commands, sorted by order.
std::vector<CommandSpec> registered_commands();

}  // namespace bodyrec::cli
