#include "group_options.h"

#include "bodyrec/core/error.h"
#include "option_checks.h"

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
      ->check(positive());
  sub.add_option("--velocity-span", options.groups.velocity_span_s,
                 "Velocity from displacement over at least N seconds")
      ->check(positive());
  sub.add_option("--half-life", options.groups.evidence_half_life_s,
                 "Pair evidence fades with this half-life in seconds (0: mean over all common time)")
      ->check(non_negative());
  sub.add_option("--min-moving", options.groups.min_moving_fraction,
                 "Windows where the two walk for less than this share of the time add no evidence (0: all count)")
      ->check(in_range(0.0, 1.0));
  sub.add_option("--linkage", options.linkage,
                 "How pairs form groups: single (connected components of together pairs), average (clusters whose pairs agree on average), none (each pair alone)");
  sub.add_option("--seconds-per-frame", options.seconds_per_frame,
                 "obsmat frame period; default: estimated from its velocities")
      ->check(non_negative());
}

}  // namespace bodyrec::cli
