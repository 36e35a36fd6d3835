#include "command.h"

#include <algorithm>

namespace bodyrec::cli {
namespace {

std::vector<CommandSpec>& registry() {
  static std::vector<CommandSpec> commands;  // function-local: safe across static initialisation order
  return commands;
}

}  // namespace

bool register_command(CommandSpec spec) {
  registry().push_back(std::move(spec));
  return true;
}

std::vector<CommandSpec> registered_commands() {
  auto commands = registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const CommandSpec& a, const CommandSpec& b) { return a.order < b.order; });
  return commands;
}

}  // namespace bodyrec::cli
