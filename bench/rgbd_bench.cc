// Synthetic RGB-D rendering cost per frame (bodyrec synth): 512x424 depth with noise, body index,
// 960x540 colour, bodies and truth, for 1, 2 and 4 people; frames cycle over a 150-frame walk-turn
// recording. Writing PNG files is not included (see docs/benchmarks.md for the whole command).
// Also: background removal (green screen) per frame.
#include <benchmark/benchmark.h>

#include "bodyrec/rgbd/green_screen.h"
#include "bodyrec/rgbd/synth.h"

namespace {

void BM_SynthRender(benchmark::State& state, const char* scenario) {
  bodyrec::SynthOptions o;
  o.people = static_cast<int>(state.range(0));
  o.scenario = scenario;
  o.frames = 150;
  o.seed = 1;
  bodyrec::Synthesizer synth(o);
  int i = 0;
  size_t bodies = 0;
  for (auto _ : state) {
    const bodyrec::RgbdFrame f = synth.render(i);
    bodies += f.bodies.size();
    i = (i + 1) % o.frames;
  }
  state.counters["bodies_per_frame"] = static_cast<double>(bodies) / static_cast<double>(state.iterations());
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_SynthRender, walk_turn, "walk-turn")->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SynthRender, cross, "cross")->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Background removal ("green screen") of one 512x424 frame with 2 people into per-body BGRA images;
// frames are rendered beforehand, cycling over 30 frames of the middle of a walk-turn recording.
void BM_BackgroundRemoval(benchmark::State& state) {
  bodyrec::SynthOptions o;
  o.people = 2;
  o.frames = 150;
  o.seed = 1;
  bodyrec::Synthesizer synth(o);
  std::vector<bodyrec::RgbdFrame> frames;
  for (int i = 60; i < 90; ++i) frames.push_back(synth.render(i));
  bodyrec::BackgroundRemoval removal(synth.meta());
  std::array<cv::Mat, bodyrec::kMaxBodies> out;
  size_t i = 0;
  for (auto _ : state) {
    const auto& f = frames[i];
    removal.apply(f.depth, f.body_index, f.color, out);
    i = (i + 1) % frames.size();
  }
}
BENCHMARK(BM_BackgroundRemoval)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
