// Options shared by `eval groups` and `train-groups`: the pair-feature window and how pairs become groups.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/groups/group_membership.h"

namespace bodyrec::cli {

struct GroupCliOptions {
  GroupOptions groups;
  std::string linkage = "single";
  double seconds_per_frame = 0;  // 0 = estimate from obsmat velocities

  // GroupOptions with the linkage name resolved and checked (UsageError for an unknown name).
  GroupOptions resolved() const;
};

// --window, --velocity-span, --half-life, --min-moving, --linkage, --seconds-per-frame.
void add_group_options(CLI::App& sub, GroupCliOptions& options);

}  // namespace bodyrec::cli
