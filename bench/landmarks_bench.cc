// Body-contour landmarking cost on 640x480 images: shape fitting per person, and detection + shape
// fitting per image (OpenCV uses 2 threads). Models are not in the repository (they are trained from
// Penn-Fudan, whose licence forbids redistribution): point BODYREC_SHAPE_MODEL at a `bodyrec train-shape`
// output, and optionally BODYREC_DETECTOR_MODEL at a `bodyrec train-detector` output. Images: the
// Penn-Fudan test split (BODYREC_DATA) letterboxed to 640x480, else vtest.avi frames resized to 640x480.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bench_support.h"
#include "bodyrec/detection/fhog_detector.h"
#include "bodyrec/detection/hog_people_detector.h"
#include "bodyrec/landmarks/body_shape.h"

namespace fs = std::filesystem;

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : "";
}

cv::Mat letterbox(const cv::Mat& image, cv::Size size) {
  const double f = std::min(static_cast<double>(size.width) / image.cols, static_cast<double>(size.height) / image.rows);
  cv::Mat resized, out(size, CV_8UC3, cv::Scalar::all(0));
  cv::resize(image, resized, cv::Size(), f, f, f < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
  resized.copyTo(out(cv::Rect((size.width - resized.cols) / 2, (size.height - resized.rows) / 2, resized.cols,
                              resized.rows)));
  return out;
}

const std::vector<cv::Mat>& images_640x480() {
  static std::vector<cv::Mat> images;
  if (!images.empty()) return images;
  const fs::path dir = fs::path(env("BODYREC_DATA").empty() ? "../shared/datasets" : env("BODYREC_DATA")) /
                       "pennfudan" / "PNGImages";
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (size_t i = 3; i < files.size(); i += 4) images.push_back(letterbox(cv::imread(files[i].string()), {640, 480}));
  if (images.empty())
    for (const auto& frame : bodyrec::bench::vtest_frames(0, 40)) images.push_back(letterbox(frame, {640, 480}));
  return images;
}

std::unique_ptr<bodyrec::BodyShapeModel> shape_model(benchmark::State& state) {
  const std::string path = env("BODYREC_SHAPE_MODEL");
  if (path.empty() || !fs::exists(path)) {
    state.SkipWithError("set BODYREC_SHAPE_MODEL to a model made by `bodyrec train-shape`");
    return nullptr;
  }
  return std::make_unique<bodyrec::BodyShapeModel>(path);
}

// Arg 1: fit() as shipped (mask-net: logits averaged with the mirror image's, a slit cut between the legs);
// arg 0: mask-net on the box alone, to show what the mirror costs; arg 2: without the slit, to show its cost.
void BM_ShapeFitPerPerson(benchmark::State& state) {
  const auto model = shape_model(state);
  if (!model) return;
  if (state.range(0) != 1) {
    if (model->kind() != bodyrec::BodyShapeModel::Kind::kMaskNet) {
      state.SkipWithError("the box-alone and no-slit cases need a mask-net model");
      return;
    }
    if (state.range(0) == 0) model->set_mirror_average(false);
    if (state.range(0) == 2) model->set_leg_slit(false);
  }
  const auto& images = images_640x480();
  std::vector<cv::Mat> prepared;
  for (const auto& image : images) prepared.push_back(model->prepare(image));
  const bodyrec::Box box(250, 60, 140, 360);  // a person-sized box in the middle of the frame
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model->fit(prepared[i], box));
    i = (i + 1) % prepared.size();
  }
  state.counters["landmarks"] = model->landmarks();
  state.SetLabel(model->kind_name());
}

void detect_and_fit(benchmark::State& state, bodyrec::PeopleDetector& detector) {
  const auto model = shape_model(state);
  if (!model) return;
  cv::setNumThreads(2);
  const auto& images = images_640x480();
  size_t i = 0, people = 0;
  for (auto _ : state) {
    const auto found = detector.detect(images[i]);
    const cv::Mat prepared = model->prepare(images[i]);
    for (const auto& d : found) benchmark::DoNotOptimize(model->fit(prepared, d.box));
    people += found.size();
    i = (i + 1) % images.size();
  }
  state.counters["people_per_image"] = static_cast<double>(people) / static_cast<double>(state.iterations());
  state.SetLabel(model->kind_name());
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_DetectAndLandmarkHog(benchmark::State& state) {
  bodyrec::HogOptions options = bodyrec::hog_preset(bodyrec::HogPreset::kDefault);
  options.motion_roi = false;  // unrelated still images: search the whole image (--motion off)
  bodyrec::HogPeopleDetector detector(options);
  detect_and_fit(state, detector);
}

void BM_DetectAndLandmarkFhog(benchmark::State& state) {
  const std::string path = env("BODYREC_DETECTOR_MODEL");
  if (path.empty() || !fs::exists(path)) {
    state.SkipWithError("set BODYREC_DETECTOR_MODEL to a model made by `bodyrec train-detector`");
    return;
  }
  bodyrec::FhogOptions options;
  options.model_path = path;
  bodyrec::FhogDetector detector(options);
  detect_and_fit(state, detector);
}

BENCHMARK(BM_ShapeFitPerPerson)->Arg(1)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_DetectAndLandmarkHog)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_DetectAndLandmarkFhog)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);

}  // namespace

BENCHMARK_MAIN();
