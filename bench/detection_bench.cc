// People detection cost per frame on vtest.avi (768x576) for the two HOG presets and the thesis
// author's dlib fHOG detector. Frames are decoded before timing; each iteration detects one frame, in
// video order (the default preset's motion model needs consecutive frames), cycling over 200 frames.
// The reported real time per iteration is the time per frame.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "bench_support.h"
#include "bodyrec/detection/fhog_detector.h"
#include "bodyrec/detection/hog_people_detector.h"

namespace {

void run(benchmark::State& state, bodyrec::PeopleDetector& detector) {
  const auto& frames = bodyrec::bench::vtest_frames(0, 200);
  if (frames.empty()) {
    state.SkipWithError("vtest.avi not found (install opencv-doc: scripts/install-deps)");
    return;
  }
  for (int i = 0; i < 10; ++i) detector.detect(frames[i]);  // warm-up: the motion model's first frames
  size_t i = 10, people = 0;
  for (auto _ : state) {
    people += detector.detect(frames[i]).size();
    i = (i + 1) % frames.size();
  }
  state.counters["people_per_frame"] = static_cast<double>(people) / static_cast<double>(state.iterations());
}

void BM_HogThesisPreset(benchmark::State& state) {
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset("thesis"));
  run(state, detector);
}

void BM_HogDefaultPreset(benchmark::State& state) {
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset("default"));
  run(state, detector);
}

// The default preset without scene-adaptive scales (every region searched at all 13 levels).
void BM_HogDefaultPresetFixedScales(benchmark::State& state) {
  bodyrec::HogOptions options = bodyrec::hog_preset("default");
  options.adapt_after = 0;
  bodyrec::HogPeopleDetector detector(options);
  run(state, detector);
}

void BM_ThesisAuthorFhog(benchmark::State& state) {
  const char* env = std::getenv("BODYREC_DATA");
  const std::filesystem::path model =
      std::filesystem::path(env && *env ? env : "../shared/datasets") / "thesis_ch3" / "object_detector.svm";
  if (!std::filesystem::exists(model)) {
    state.SkipWithError("thesis_ch3/object_detector.svm not found under BODYREC_DATA");
    return;
  }
  bodyrec::FhogOptions options;
  options.model_path = model.string();
  bodyrec::FhogDetector detector(options);
  run(state, detector);
}

BENCHMARK(BM_HogThesisPreset)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_HogDefaultPreset)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_HogDefaultPresetFixedScales)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_ThesisAuthorFhog)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);

}  // namespace

BENCHMARK_MAIN();
