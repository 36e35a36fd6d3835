// People detection cost per frame on vtest.avi (768x576) for the two HOG presets, background subtraction
// and the thesis author's dlib fHOG detector. Frames are decoded before timing; each iteration detects one frame, in
// video order (the default preset's motion model needs consecutive frames), cycling over 200 frames.
// The reported real time per iteration is the time per frame. The photo cases cycle the same way over the
// 42 Penn-Fudan test photos (BODYREC_DATA, default ../shared/datasets; 300-1000 px across).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "bench_support.h"
#include "bodyrec/detection/dpm_people_detector.h"
#include "bodyrec/detection/fhog_detector.h"
#include "bodyrec/detection/foreground_detector.h"
#include "bodyrec/detection/hog_people_detector.h"
#include "bodyrec/io/pennfudan.h"

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
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kThesis));
  run(state, detector);
}

void BM_HogDefaultPreset(benchmark::State& state) {
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kDefault));
  run(state, detector);
}

// The default preset without scene-adaptive scales (every region searched at all 13 levels).
void BM_HogDefaultPresetFixedScales(benchmark::State& state) {
  bodyrec::HogOptions options = bodyrec::hog_preset(bodyrec::HogPreset::kDefault);
  options.adapt_after = 0;
  bodyrec::HogPeopleDetector detector(options);
  run(state, detector);
}

// Background subtraction (--preset foreground, plain-camera reid's detector).
void BM_ForegroundPreset(benchmark::State& state) {
  bodyrec::ForegroundPeopleDetector detector;
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

// The Penn-Fudan test split's photos, decoded once; empty when the dataset is missing.
const std::vector<cv::Mat>& pennfudan_test_photos() {
  static const std::vector<cv::Mat> photos = [] {
    const char* env = std::getenv("BODYREC_DATA");
    const std::filesystem::path dir = std::filesystem::path(env && *env ? env : "../shared/datasets") / "pennfudan";
    std::vector<cv::Mat> out;
    if (!std::filesystem::exists(dir / "PNGImages")) return out;
    for (const auto& photo : bodyrec::load_pennfudan(dir.string(), bodyrec::PennFudanSplit::kTest))
      out.push_back(cv::imread(photo.image_path, cv::IMREAD_COLOR));
    return out;
  }();
  return photos;
}

void run_photos(benchmark::State& state, bodyrec::PeopleDetector& detector) {
  const auto& photos = pennfudan_test_photos();
  if (photos.empty()) {
    state.SkipWithError("pennfudan not found under BODYREC_DATA");
    return;
  }
  size_t i = 0, people = 0;
  for (auto _ : state) {
    people += detector.detect(photos[i]).size();
    i = (i + 1) % photos.size();
  }
  state.counters["people_per_photo"] = static_cast<double>(people) / static_cast<double>(state.iterations());
}

void BM_PhotoPresetPennFudan(benchmark::State& state) {
  if (!std::filesystem::exists("/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml")) {
    state.SkipWithError("opencv-doc's inriaperson.xml not found (scripts/install-deps)");
    return;
  }
  bodyrec::DpmPeopleDetector detector(bodyrec::dpm_photo_preset());
  run_photos(state, detector);
}

void BM_OpenCvPresetPennFudan(benchmark::State& state) {
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kOpenCv));
  run_photos(state, detector);
}

BENCHMARK(BM_HogThesisPreset)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_HogDefaultPreset)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_HogDefaultPresetFixedScales)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_ForegroundPreset)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_ThesisAuthorFhog)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
// Whole passes over the 42 photos (sizes differ: a time-limited run would average over a prefix of them).
BENCHMARK(BM_PhotoPresetPennFudan)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(84);
BENCHMARK(BM_OpenCvPresetPennFudan)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(168);

}  // namespace

BENCHMARK_MAIN();
