#include "option_error_text.h"

#include <algorithm>
#include <map>
#include <vector>

namespace bodyrec::cli {
namespace {

// Options whose flags carry the struct's prefix (--leader-min-psr for LeaderTrackerOptions.min_psr).
const std::map<std::string, std::string> kFlagPrefix = {
    {"LeaderTrackerOptions", "leader-"},     {"LeaderDirectionOptions", "direction-"},
    {"DifferentialMotionOptions", "motion-"}, {"MotionRegionOptions", "motion-"},
    {"FhogOptions", "fhog-"},
};

// Fields whose flag has another name altogether.
const std::map<std::string, std::string> kFlagOf = {
    {"MaskNetTrainOptions.input_width", "--net-size"}, {"MaskNetTrainOptions.input_height", "--net-size"},
    {"MaskNetTrainOptions.threshold", "--mask-threshold"}, {"ContourSetOptions.pennfudan_dir", "--pennfudan"},
    {"ContourSetOptions.out_dir", "--out"},           {"DifferentialMotionOptions.work_width", "--motion-width"},
    {"GroupOptions.evidence_half_life_s", "--half-life"}, {"GroupOptions.min_moving_fraction", "--min-moving"},
    {"ForegroundOptions.history", "--background-history"}, {"HogOptions.local_region_margin", "--local-margin"},
};

// The innermost subcommand that was parsed (bodyrec -> eval -> reid).
const CLI::App* ran_command(const CLI::App& app) {
  const CLI::App* at = &app;
  for (std::vector<CLI::App*> parsed = at->get_subcommands(); !parsed.empty(); parsed = at->get_subcommands())
    at = parsed.front();
  return at;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::vector<std::string> candidate_flags(const OptionError& e) {
  std::vector<std::string> flags;
  if (const auto it = kFlagOf.find(e.options() + "." + e.field()); it != kFlagOf.end()) flags.push_back(it->second);
  std::string name = e.field();
  std::replace(name.begin(), name.end(), '_', '-');
  if (name.size() == 1) flags.push_back("-" + name);
  std::vector<std::string> names = {name};
  for (const std::string unit : {"-frames", "-s", "-m", "-ms", "-px"})
    if (ends_with(name, unit)) names.push_back(name.substr(0, name.size() - unit.size()));
  const auto prefix = kFlagPrefix.find(e.options());
  for (const std::string& n : names) {  // the prefixed name first: groups has a --window of its own
    if (prefix != kFlagPrefix.end()) flags.push_back("--" + prefix->second + n);
    flags.push_back("--" + n);
  }
  return flags;
}

}  // namespace

std::string option_error_text(const OptionError& e, const CLI::App& app) {
  const CLI::App* command = ran_command(app);
  for (const std::string& flag : candidate_flags(e)) {
    if (command->get_option_no_throw(flag) != nullptr) return flag + " " + e.problem();
  }
  return e.what();
}

}  // namespace bodyrec::cli
