#include "group_options.h"

#include "bodyrec/core/error.h"

namespace bodyrec::cli {

GroupOptions GroupCliOptions::resolved() const {
  GroupOptions o = groups;
  if (linkage == "average") o.linkage = GroupLinkage::kAverage;
  else if (linkage == "single") o.linkage = GroupLinkage::kSingle;
  else if (linkage == "none") o.linkage = GroupLinkage::kNone;
  else throw UsageError("--linkage must be average, single or none, got '" + linkage + "'");
  o.check();
  return o;
}

void add_group_options(CLI::App& sub, GroupCliOptions& options) {
  sub.add_option("--window", options.groups.window_s,
                 "Pair features over the last N seconds (the built-in models were trained with the default)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--velocity-span", options.groups.velocity_span_s,
                 "Velocity from displacement over at least N seconds")
      ->check(CLI::PositiveNumber);
  sub.add_option("--half-life", options.groups.evidence_half_life_s,
                 "Pair evidence fades with this half-life in seconds (0: mean over all common time)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--linkage", options.linkage,
                 "How pairs form groups: average (group consistency), single (connected pairs), none (pairs alone)");
  sub.add_option("--seconds-per-frame", options.seconds_per_frame,
                 "obsmat frame period; default: estimated from its velocities")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace bodyrec::cli
