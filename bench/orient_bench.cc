// Orientation per body (skeleton, depth only, thesis rule; with and without the face detector) and
// partial-scan extraction per body at 960x540 colour. Frames are rendered beforehand by the synthesizer
// (seed 1, walk-turn, 3 people, 90 frames, frames 30-59 timed). One iteration is one frame (all its bodies); ms per body = time / bodies_per_frame
// (items_per_second counts bodies).
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/reid/partial_scan.h"
#include "bodyrec/rgbd/synth.h"

namespace {

struct Frames {
  std::unique_ptr<bodyrec::Synthesizer> synth;
  std::vector<bodyrec::RgbdFrame> frames;
  size_t bodies = 0;
};

const Frames& frames() {
  static Frames s;
  if (!s.frames.empty()) return s;
  bodyrec::SynthOptions o;
  o.people = 3;
  o.frames = 90;
  o.seed = 1;
  s.synth = std::make_unique<bodyrec::Synthesizer>(o);
  for (int i = 30; i < 60; ++i) {
    bodyrec::RgbdFrame f = s.synth->render(i);
    f.depth = f.depth.clone();
    f.body_index = f.body_index.clone();
    f.color = f.color.clone();
    s.bodies += f.bodies.size();
    s.frames.push_back(std::move(f));
  }
  return s;
}

// Arg 0: method (0 robust skeleton, 1 robust depth only, 2 thesis); arg 1: face detector on/off.
void BM_OrientBody(benchmark::State& state) {
  const Frames& s = frames();
  bodyrec::OrientationOptions o;
  o.method = state.range(0) == 2 ? bodyrec::ViewMethod::kThesis : bodyrec::ViewMethod::kRobust;
  o.use_skeleton = state.range(0) != 1;
  o.use_faces = state.range(1) != 0;
  bodyrec::OrientationEstimator est(s.synth->meta(), o);
  size_t i = 0, bodies = 0, views = 0;
  for (auto _ : state) {
    const bodyrec::RgbdFrame& f = s.frames[i];
    for (const auto& b : f.bodies) {
      views += est.estimate(f, bodyrec::BodyRef::of(b, f.body_index)).view.has_value();
      ++bodies;
    }
    i = (i + 1) % s.frames.size();
  }
  state.SetItemsProcessed(static_cast<int64_t>(bodies));
  state.counters["bodies_per_frame"] = static_cast<double>(bodies) / static_cast<double>(state.iterations());
  state.counters["views_share"] = bodies ? static_cast<double>(views) / static_cast<double>(bodies) : 0.0;
}
BENCHMARK(BM_OrientBody)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->ArgNames({"method", "faces"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PartialScanBody(benchmark::State& state) {
  const Frames& s = frames();
  bodyrec::PartialScanExtractor scans(s.synth->meta());
  size_t i = 0, bodies = 0, pixels = 0;
  for (auto _ : state) {
    const bodyrec::RgbdFrame& f = s.frames[i];
    for (const auto& b : f.bodies) {
      if (const auto scan = scans.extract(f, bodyrec::BodyRef::of(b, f.body_index), bodyrec::ViewEstimate{}))
        pixels += static_cast<size_t>(scan->pixels);
      ++bodies;
    }
    i = (i + 1) % s.frames.size();
  }
  state.SetItemsProcessed(static_cast<int64_t>(bodies));
  state.counters["bodies_per_frame"] = static_cast<double>(bodies) / static_cast<double>(state.iterations());
  state.counters["colour_px_per_body"] = bodies ? static_cast<double>(pixels) / static_cast<double>(bodies) : 0.0;
}
BENCHMARK(BM_PartialScanBody)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
