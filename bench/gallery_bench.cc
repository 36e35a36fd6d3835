// The re-identification gallery (src/bodyrec/store): cost of put_scan (one transaction with an fsync,
// synchronous FULL vs NORMAL, with and without images), opening a 100-user x 8-view gallery (the
// feature cache load), and forget on a 100-user gallery (delete + VACUUM + WAL checkpoint).
// Files live in the system temp directory (a real disk on the development machine, so fsync costs).
#include <filesystem>
#include <random>

#include <benchmark/benchmark.h>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_test_support.h"

namespace {

namespace fs = std::filesystem;
using bodyrec::Gallery;
using bodyrec::GalleryOptions;
using bodyrec::kAllViews;
using bodyrec::GalleryScan;
using bodyrec::View;
using bodyrec::store::testing::make_scan;

struct ScratchDir {
  fs::path path;
  ScratchDir() {
    path = fs::temp_directory_path() / ("bodyrec-gallery-bench-" + std::to_string(std::random_device()()));
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// A person-sized scan (128x64, the size the reid pipeline keeps) with `dim`-long float features.
GalleryScan bench_scan(View view, double quality, int seed, int feature_rows, int feature_cols) {
  GalleryScan s = make_scan(view, quality, seed, 128, 64);
  s.features = cv::Mat(feature_rows, feature_cols, CV_32F);
  cv::randu(s.features, 0, 1);
  return s;
}

// Builds users x 8 views once per shape; returns the path.
std::string full_gallery(const ScratchDir& dir, int users, int rows, int cols, bool images) {
  const std::string path = (dir.path / ("g" + std::to_string(users) + "x" + std::to_string(rows) + "x" +
                                        std::to_string(cols) + (images ? "i" : "") + ".db"))
                               .string();
  if (fs::exists(path)) return path;
  GalleryOptions o;
  o.create = true;
  o.sync_full = false;  // building the fixture only
  o.store_images = images;
  Gallery g(path, o);
  g.transaction([&] {
    for (int u = 0; u < users; ++u) {
      const auto id = g.enrol(bench_scan(View::F, 0.5, u * 8, rows, cols));
      for (View v : kAllViews)
        if (v != View::F) g.put_scan(id, bench_scan(v, 0.5, u * 8 + static_cast<int>(v), rows, cols));
    }
  });
  return path;
}

// Arg 0: synchronous FULL (1) or NORMAL (0); arg 1: store images (1) or features only (0).
void BM_PutScanReplace(benchmark::State& state) {
  ScratchDir dir;
  GalleryOptions o;
  o.create = true;
  o.sync_full = state.range(0) != 0;
  o.store_images = state.range(1) != 0;
  Gallery g((dir.path / "g.db").string(), o);
  const auto user = g.add_user();
  std::vector<GalleryScan> scans;
  for (int i = 0; i < 16; ++i) scans.push_back(bench_scan(View::F, 0, i, 1, 512));
  double quality = 0;
  int i = 0;
  for (auto _ : state) {
    GalleryScan& s = scans[static_cast<size_t>(i++ % 16)];
    s.quality = quality += 1;  // always better: a replacing write
    benchmark::DoNotOptimize(g.put_scan(user, s));
  }
  state.counters["fsync"] = o.sync_full ? 1 : 0;
}
BENCHMARK(BM_PutScanReplace)->Args({1, 1})->Args({0, 1})->Args({1, 0})->Unit(benchmark::kMillisecond);

// A scan no better than the stored one: a read inside a write transaction, nothing written.
void BM_PutScanKept(benchmark::State& state) {
  ScratchDir dir;
  GalleryOptions o;
  o.create = true;
  Gallery g((dir.path / "g.db").string(), o);
  const auto user = g.enrol(bench_scan(View::F, 1.0, 1, 1, 512));
  const GalleryScan worse = bench_scan(View::F, 0.5, 2, 1, 512);
  for (auto _ : state) benchmark::DoNotOptimize(g.put_scan(user, worse));
}
BENCHMARK(BM_PutScanKept)->Unit(benchmark::kMillisecond);

// Open + load the feature cache of 100 users x 8 views. Args: feature rows, cols (1x512: an appearance
// histogram; 100x64: KAZE descriptors).
void BM_OpenAndLoadCache(benchmark::State& state) {
  ScratchDir dir;
  const int rows = static_cast<int>(state.range(0)), cols = static_cast<int>(state.range(1));
  const std::string path = full_gallery(dir, 100, rows, cols, true);
  size_t entries = 0;
  for (auto _ : state) {
    Gallery g(path);
    entries = g.scans(View::F).size() * 8;
  }
  state.counters["scans"] = static_cast<double>(entries);
  state.counters["file_MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
}
BENCHMARK(BM_OpenAndLoadCache)->Args({1, 512})->Args({100, 64})->Unit(benchmark::kMillisecond);

// forget one user of 100 (8 views with images): delete, secure_delete zeroing, VACUUM, checkpoint.
void BM_Forget100(benchmark::State& state) {
  ScratchDir dir;
  const std::string fixture = full_gallery(dir, 100, 1, 512, true);
  const std::string path = (dir.path / "work.db").string();
  for (auto _ : state) {
    state.PauseTiming();
    fs::copy_file(fixture, path, fs::copy_options::overwrite_existing);
    {
      Gallery g(path);
      state.ResumeTiming();
      benchmark::DoNotOptimize(g.forget(50));
      state.PauseTiming();
    }
    state.ResumeTiming();
  }
  state.counters["file_MB"] = static_cast<double>(fs::file_size(fixture)) / 1e6;
}
BENCHMARK(BM_Forget100)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
