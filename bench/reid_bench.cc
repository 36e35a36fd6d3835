// Re-identification costs: descriptor extraction per image (VIPeR's 48x128, and a ~100x250 RGB-D body
// crop with its mask), one probe against a 100-user x 8-view gallery (800 descriptors), and one KAZE
// pair (the thesis's score). Images are generated (textured bodies), so no dataset is needed.
#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/gog_features.h"
#include "bodyrec/reid/kaze_matcher.h"
#include "bodyrec/reid/lomo_features.h"

namespace {

// A body-shaped textured crop with its mask (background 0).
bodyrec::PersonImage body(int seed, cv::Size size) {
  cv::RNG rng(static_cast<uint64_t>(seed));
  bodyrec::PersonImage p;
  p.bgr = cv::Mat(size, CV_8UC3, cv::Scalar(0, 0, 0));
  p.mask = cv::Mat::zeros(size, CV_8U);
  const cv::Point centre(size.width / 2, size.height / 2);
  cv::ellipse(p.mask, centre, {size.width * 2 / 5, size.height * 9 / 20}, 0, 0, 360, 255, cv::FILLED);
  cv::Mat texture(size, CV_8UC3);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(texture, texture, {0, 0}, 3);
  texture.copyTo(p.bgr, p.mask);
  return p;
}

// One LOMO feature (Retinex colours); third argument 1: averaged with the mirror image's (LomoOptions::mirror).
void BM_LomoFeatures(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  bodyrec::PersonImage image = body(1, size);
  if (size.width == 48) image.mask = cv::Mat();  // VIPeR has no masks
  bodyrec::LomoOptions options;
  options.mirror = state.range(2) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::lomo_features(image, options));
}
BENCHMARK(BM_LomoFeatures)
    ->Args({48, 128, 0})
    ->Args({48, 128, 1})
    ->Args({100, 250, 0})
    ->Args({100, 250, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// GOG in one colour space (the default matcher computes four).
void BM_GogFeatures(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  bodyrec::PersonImage image = body(1, size);
  if (size.width == 48) image.mask = cv::Mat();
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::gog_features(image, bodyrec::GogColour::kRgb));
}
BENCHMARK(BM_GogFeatures)->Args({48, 128})->Args({100, 250})->Unit(benchmark::kMillisecond)->UseRealTime();

// What the default matcher computes per image before its model: LOMO's parts (both colour versions, with
// and without mirror averaging) and GOG in four colour spaces.
void BM_DefaultMatcherFeatures(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  bodyrec::PersonImage image = body(1, size);
  if (size.width == 48) image.mask = cv::Mat();
  const auto matcher = bodyrec::make_untrained_matcher("default");
  for (auto _ : state) benchmark::DoNotOptimize(matcher->features(image));
}
BENCHMARK(BM_DefaultMatcherFeatures)->Args({48, 128})->Args({100, 250})->Unit(benchmark::kMillisecond)->UseRealTime();

// XQDA embedding of one LOMO feature (a random projection of the size VIPeR training gives).
void BM_XqdaEmbed(benchmark::State& state) {
  bodyrec::XqdaModel model;
  model.projection = cv::Mat(bodyrec::lomo_length(), static_cast<int>(state.range(0)), CV_32F);
  cv::randn(model.projection, 0, 0.01);
  model.prepare();
  const std::vector<float> f = bodyrec::lomo_features(body(2, {48, 128}));
  for (auto _ : state) benchmark::DoNotOptimize(model.embed(f));
}
BENCHMARK(BM_XqdaEmbed)->Arg(100)->Arg(300)->Unit(benchmark::kMillisecond)->UseRealTime();

// The shipped default model's share of a descriptor, from the features: the GOG centring, the count
// sketch of every block and the three XQDA embeddings (99 dimensions in all).
void BM_ShippedDefaultDescriptor(benchmark::State& state) {
  const auto matcher = bodyrec::make_matcher("default");
  const std::vector<float> f = matcher->features(body(2, {48, 128}));
  for (auto _ : state) benchmark::DoNotOptimize(matcher->descriptor(f));
}
BENCHMARK(BM_ShippedDefaultDescriptor)->Unit(benchmark::kMillisecond)->UseRealTime();

// One probe descriptor against 800 gallery descriptors (100 users x 8 views): best similarity.
void BM_MatchGallery800(benchmark::State& state) {
  const int dims = static_cast<int>(state.range(0));
  cv::RNG rng(3);
  auto random_vector = [&] {
    std::vector<float> v(static_cast<size_t>(dims));
    for (float& x : v) x = static_cast<float>(rng.gaussian(1.0));
    return v;
  };
  const auto matcher = bodyrec::make_matcher("lomo");
  std::vector<std::vector<float>> gallery;
  for (int i = 0; i < 800; ++i) gallery.push_back(random_vector());
  const std::vector<float> probe = random_vector();
  for (auto _ : state) {
    double best = -1e300;
    for (const auto& g : gallery) best = std::max(best, matcher->similarity(probe, g));
    benchmark::DoNotOptimize(best);
  }
}
BENCHMARK(BM_MatchGallery800)->Arg(300)->Arg(bodyrec::lomo_length())->Unit(benchmark::kMillisecond)->UseRealTime();

// The thesis's KAZE score of one image pair, descriptors of both computed beforehand (per-pair cost)
// and KAZE extraction itself.
void BM_KazePair(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const cv::Mat a = bodyrec::kaze_descriptors(body(4, size)), b = bodyrec::kaze_descriptors(body(5, size));
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::kaze_score(a, b));
  state.counters["keypoints"] = a.rows;
}
BENCHMARK(BM_KazePair)->Args({48, 128})->Args({100, 250})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_KazeDescriptors(benchmark::State& state) {
  const cv::Size size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const bodyrec::PersonImage image = body(6, size);
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::kaze_descriptors(image));
}
BENCHMARK(BM_KazeDescriptors)->Args({48, 128})->Args({100, 250})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
