// How the program words a library OptionError: with the command-line option that sets the field.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec::cli {

// "--hit-threshold must be finite" when the subcommand that ran has an option for e.field(): the field's
// name with '-' for '_' ("hit_threshold" -> --hit-threshold), without a unit suffix ("max_wait_frames" ->
// --max-wait), with its struct's prefix (LeaderTrackerOptions.min_psr -> --leader-min-psr), or a name listed
// in option_error_text.cc. Otherwise the library's own message, which names the struct and the field.
std::string option_error_text(const OptionError& e, const CLI::App& app);

}  // namespace bodyrec::cli
