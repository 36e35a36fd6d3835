#include "group_options.h"

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"
#include "enum_option.h"
#include "option_checks.h"

namespace bodyrec::cli {

GroupOptions GroupCliOptions::resolved(std::shared_ptr<const PairModel> model) const {
  GroupOptions o = options_for(model, groups);
  if (window_given()) o.window_s = groups.window_s;
  if (velocity_span_given()) o.velocity_span_s = groups.velocity_span_s;
  if (min_moving_given()) o.min_moving_fraction = groups.min_moving_fraction;
  if (linkage_given()) o.linkage = linkage;
  o.check();
  return o;
}

GroupOptions GroupCliOptions::resolved() const {
  return resolved(std::make_shared<const PairModel>(builtin_pair_model_for("")));
}

void add_group_options(CLI::App& sub, GroupCliOptions& options, GroupInput input) {
  options.window_option =
      sub.add_option("--window", options.groups.window_s, "Pair features over the last N seconds, or inf: over the pair's whole common time (default: the "
                     "model's; train-groups chooses it)")
          ->check(CLI::Validator(
              [](std::string& text) -> std::string {
                const auto v = parse_double(text);
                return v && *v > 0 ? "" : "must be a positive number of seconds or inf, got '" + text + "'";
              },
              "SECONDS|inf"));
  options.velocity_span_option =
      sub.add_option("--velocity-span", options.groups.velocity_span_s,
                     "Velocity from displacement over at least N seconds (default: the model's; train-groups chooses it; the "
                     "plain rule: 0.4)")
          ->check(positive());
  sub.add_option("--half-life", options.groups.evidence_half_life_s,
                 "Pair evidence fades with this half-life in seconds (0: mean over all common time)")
      ->check(non_negative());
  options.min_moving_option =
      sub.add_option("--min-moving", options.groups.min_moving_fraction,
                     "Windows where the two walk for less than this share of the time add no evidence (0: all "
                     "count; default: the model's; train-groups chooses it)")
          ->check(in_range(0.0, 1.0));
  options.linkage_option = add_enum_option(
      sub, "--linkage", options.linkage,
      std::vector<std::pair<std::string, GroupLinkage>>{
          {"single", GroupLinkage::kSingle}, {"average", GroupLinkage::kAverage}, {"none", GroupLinkage::kNone}},
      "How pairs form groups: single (connected components of together pairs), average (clusters whose pairs "
      "agree on average), none (each pair alone); train-groups chooses it",
      "the model's");
  if (input == GroupInput::kSceneFiles)
    sub.add_option("--seconds-per-frame", options.seconds_per_frame,
                   "obsmat frame period; default: estimated from its velocities")
        ->check(non_negative());
}

}  // namespace bodyrec::cli
