// Options shared by `eval groups`, `train-groups` and `groups`: the pair-feature window and how pairs
// become groups.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/groups/group_membership.h"

namespace bodyrec::cli {

struct GroupCliOptions {
  GroupOptions groups;
  GroupLinkage linkage = GroupLinkage::kSingle;  // used only when given (linkage_given)
  double seconds_per_frame = 0;  // 0 = estimate from obsmat velocities
  // Set by add_group_options (null when the options were not added).
  CLI::Option* window_option = nullptr;
  CLI::Option* velocity_span_option = nullptr;
  CLI::Option* min_moving_option = nullptr;
  CLI::Option* linkage_option = nullptr;

  // GroupOptions that use `model` with its window, velocity span, min-moving share and linkage, each
  // unless given on the command line; checked (UsageError for an unknown linkage name or a bad value).
  GroupOptions resolved(std::shared_ptr<const PairModel> model) const;
  // The same with the built-in model for new scenes.
  GroupOptions resolved() const;

  bool window_given() const { return window_option && window_option->count() > 0; }
  bool min_moving_given() const { return min_moving_option && min_moving_option->count() > 0; }
  bool linkage_given() const { return linkage_option && linkage_option->count() > 0; }
  bool velocity_span_given() const { return velocity_span_option && velocity_span_option->count() > 0; }
  GroupLinkage linkage_value() const { return linkage; }
  // --velocity-span, or 0.4 s (the plain rule's).
  double velocity_span() const { return velocity_span_given() ? groups.velocity_span_s : 0.4; }
};

// What the group options are for: scene files (train-groups, eval groups) also take --seconds-per-frame;
// a video or camera run has its own frame times.
enum class GroupInput { kSceneFiles, kFrames };

// --window, --velocity-span, --half-life, --min-moving, --linkage, and with scene files --seconds-per-frame.
void add_group_options(CLI::App& sub, GroupCliOptions& options, GroupInput input);

}  // namespace bodyrec::cli
