// `bodyrec synth`: writes a synthetic RGB-D recording of people with ground truth.
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/progress.h"
#include "bodyrec/rgbd/synth.h"
#include "command.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct SynthCommand {
  SynthOptions options;
  std::string out;
  bool json = false, quiet = false;

  void run(bool frames_given) {
    if (!frames_given) options.frames = synth_recommended_frames(options.scenario, options.people);
    options.check();
    Synthesizer synth(options);
    RecordingWriter writer(out, synth.meta());
    const bool progress = progress_on_terminal(quiet);
    double render_ms = 0;
    int bodies = 0;
    for (int i = 0; i < options.frames; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const RgbdFrame f = synth.render(i);
      render_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      bodies += static_cast<int>(f.bodies.size());
      writer.write(f);
      if (progress && (i + 1) % 30 == 0) std::fprintf(stderr, "\rsynth: %d/%d frames", i + 1, options.frames);
    }
    if (progress && options.frames >= 30) std::fprintf(stderr, "\n");
    const double ms = render_ms / options.frames;
    std::printf("wrote %s: %d frames, %s, %d people, seed %llu; %.2f bodies per frame; render %.2f ms per frame\n",
                out.c_str(), options.frames, options.scenario.c_str(), options.people,
                static_cast<unsigned long long>(options.seed), static_cast<double>(bodies) / options.frames, ms);
    if (json) {
      nlohmann::json j = {{"frames", options.frames}, {"people", options.people}, {"seed", options.seed},
                          {"scenario", options.scenario}, {"bodies", bodies}, {"render_ms_per_frame", ms}};
      if (options.looks_seed) j["looks_seed"] = *options.looks_seed;
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<SynthCommand>();
  CLI::App* sub = app.add_subcommand("synth", "Render a synthetic RGB-D recording of people with ground truth");
  // The range is checked by SynthOptions::check, which says why in one line.
  sub->add_option("--people", command->options.people,
                  "Number of people (1-8; like a Kinect, at most 6 are tracked at once: a 7th in view gets no body "
                  "until a slot frees)");
  sub->add_option("--seed", command->options.seed, "Random seed: looks, paths and sensor noise");
  sub->add_option("--looks-seed", command->options.looks_seed,
                  "Seed of the people's looks (clothes, build, stature) instead of --seed: the same people on other "
                  "paths, e.g. for a site's second sensor");
  CLI::Option* frames =
      sub->add_option("--frames", command->options.frames,
                      "Frames to render (30 per second; the scenario spans them all). Default 150; for visits "
                      "450 with 1-4 people, 540 with 5, 630 with 6, 710 with 7, 800 with 8 (visits of about 5 s)")
          ->check(positive());
  sub->add_option("--scenario", command->options.scenario,
                  "walk-turn, cross, group, reenter, or visits (everyone comes, turns round, leaves and comes back "
                  "from the other side, 2-4 people in view at once)")
      ->check(one_of(synth_scenarios()));
  sub->add_option("--out", command->out, "Recording directory to create (must not exist or be empty)")->required();
  sub->add_option("--color-width", command->options.color_width, "Colour image width");
  sub->add_option("--color-height", command->options.color_height, "Colour image height");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, people, seed, looks_seed when given, scenario, bodies, render_ms_per_frame)");
  sub->add_flag("-q,--quiet", command->quiet, "No progress on stderr (drawn only when stderr is a terminal)");
  sub->footer(
      "Examples:\n  bodyrec synth --people 2 --seed 7 --frames 150 --scenario cross --out rec_synth\n"
      "  bodyrec synth --people 8 --seed 1 --scenario visits --out rec_visits   # 800 frames\n"
      "  bodyrec synth --people 8 --seed 2 --looks-seed 1 --scenario visits --out rec_b   # its people, other paths");
  sub->callback([command, frames] { command->run(frames->count() > 0); });
}

const bool registered = register_command({"", 51, add});

}  // namespace
}  // namespace bodyrec::cli
