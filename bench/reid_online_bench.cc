// Online re-identification (bodyrec reid) per body and frame, with a 100-user gallery, the cost of
// matching one scan against galleries of 10..1000 users, and a soak run of 50 000 frames.
//
// Frames: the synthesizer's walk-turn scenario, 4 people, seed 3, frames 20-79 rendered once. The loop
// replays them; each replay gives the bodies new tracking ids, so every replay is a return visit: each
// body is pending (a scan described and scored every frame) until recognised, then checked every 10th
// frame. The gallery holds 100 other users with 8 views each (random clothing) plus these 4 people.
// Per body = orientation (face detector included) + partial scan (with heights above the floor, refitted
// every 10 frames) and stature when wanted + describe + decide.
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

#include "bench_support.h"
#include "bodyrec/reid/body_measures.h"
#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/reid/online_reid.h"
#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/reid/partial_scan.h"
#include "bodyrec/rgbd/ground_plane.h"
#include "bodyrec/rgbd/synth.h"

namespace {

using namespace bodyrec;

struct Frames {
  std::unique_ptr<Synthesizer> synth;
  std::vector<RgbdFrame> frames;
};

const Frames& frames() {
  static Frames s;
  if (!s.frames.empty()) return s;
  SynthOptions o;
  o.people = 4;
  o.frames = 100;
  o.seed = 3;
  o.scenario = "walk-turn";
  s.synth = std::make_unique<Synthesizer>(o);
  for (int i = 20; i < 80; ++i) {
    RgbdFrame f = s.synth->render(i);
    f.color = f.color.clone();
    f.depth = f.depth.clone();
    f.body_index = f.body_index.clone();
    s.frames.push_back(std::move(f));
  }
  return s;
}

// A gallery file with `users` random people (8 views each, stripes descriptors), in a fresh directory.
std::string make_gallery(int users, const AppearanceMatcher& matcher, const std::string& tag) {
  char tmpl[] = "/tmp/bodyrec-bench-XXXXXX";
  const std::string dir = mkdtemp(tmpl);
  const std::string path = dir + "/" + tag + ".db";
  GalleryOptions g;
  g.create = true;
  g.sync_full = false;
  Gallery gallery(path, g);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> c(0, 255);
  gallery.transaction([&] {
    for (int u = 0; u < users; ++u) {
      cv::Mat image(160, 64, CV_8UC3, cv::Scalar(0, 0, 0));
      const cv::Scalar shirt(c(rng), c(rng), c(rng)), trousers(c(rng), c(rng), c(rng));
      cv::circle(image, {32, 14}, 11, cv::Scalar(90, 120, 170), cv::FILLED);
      cv::rectangle(image, cv::Rect(12, 26, 40, 58), shirt, cv::FILLED);
      cv::rectangle(image, cv::Rect(16, 84, 32, 74), trousers, cv::FILLED);
      // Texture and sensor noise: real clothes fill more histogram bins than a flat colour (the
      // gallery index's cost grows with the filled bins).
      cv::Mat noise(image.size(), CV_8UC3);
      cv::RNG(static_cast<uint64_t>(u) + 1).fill(noise, cv::RNG::UNIFORM, 0, 48);
      cv::Mat grey;
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      cv::add(image, noise, image, grey > 0);
      std::vector<float> d = matcher.describe(PersonImage{image, {}});
      // OnlineReid's layout: the descriptor, then the body measurements (a stature of 1.50-1.99 m).
      d.push_back(1.5f + 0.005f * static_cast<float>(u % 100));
      d.push_back(30.f);
      GalleryScan scan;
      scan.features = cv::Mat(1, static_cast<int>(d.size()), CV_32F, d.data()).clone();
      scan.descriptor = matcher.name() + "/" + matcher.version();
      scan.descriptor_version = kReidDescriptorVersion;
      scan.quality = 0.5;
      scan.view = View::F;
      const UserId id = gallery.enrol(scan);
      for (View v : kAllViews)
        if (v != View::F) {
          scan.view = v;
          gallery.put_scan(id, scan);
        }
    }
  });
  return path;
}

struct Pipeline {
  const Frames& s = frames();
  std::unique_ptr<AppearanceMatcher> matcher = make_matcher("stripes");
  std::unique_ptr<Gallery> gallery;
  std::unique_ptr<GalleryReidStore> store;
  OrientationEstimator orient{s.synth->meta()};
  PartialScanExtractor scans{s.synth->meta()};
  GroundPlaneTracker floor{s.synth->meta().depth, s.synth->meta().depth_unit_m};
  std::unique_ptr<OnlineReid> reid;
  int frame = 0;
  size_t bodies = 0;

  explicit Pipeline(int users) {
    gallery = std::make_unique<Gallery>(make_gallery(users, *matcher, "reid"));
    store = std::make_unique<GalleryReidStore>(*gallery, *matcher);
    reid = std::make_unique<OnlineReid>(*store, *matcher);
  }
  // One frame; returns the bodies processed.
  size_t step() {
    const RgbdFrame& f = s.frames[static_cast<size_t>(frame) % s.frames.size()];
    const uint64_t replay = static_cast<uint64_t>(frame) / s.frames.size();
    std::vector<ReidBody> in;
    const std::optional<GroundPlane>& ground = floor.update(frame, f.depth);
    for (const Body& b : f.bodies) {
      BodyRef ref = BodyRef::of(b, f.body_index);
      ref.key = b.tracking_id + 100000 * replay;  // a new visit every replay
      ReidBody rb;
      rb.track = ref.key;
      rb.view = orient.estimate(f, ref);
      if (reid->wants_scan(rb.track, rb.view)) {
        rb.scan = scans.extract(f, ref, rb.view, nullptr, ground ? &*ground : nullptr);
        if (ground && rb.scan)
          rb.stature_m = measure_stature(f.depth, s.synth->meta().depth_unit_m, s.synth->meta().depth, f.body_index, b.index, *ground);
      }
      in.push_back(std::move(rb));
    }
    // Time runs on across replays; a 1 s gap between them makes every visit end (`left`).
    reid->step(frame / 30.0 + static_cast<double>(replay), in);
    ++frame;
    bodies += in.size();
    return in.size();
  }
};

// Whole online path per frame (all bodies), gallery of range(0) other users plus the 4 visitors.
void BM_ReidOnlineFrame(benchmark::State& state) {
  Pipeline p(static_cast<int>(state.range(0)));
  for (int i = 0; i < 60; ++i) p.step();  // first visit: the 4 people are enrolled
  p.bodies = 0;
  int64_t frames = 0;
  for (auto _ : state) {
    p.step();
    ++frames;
  }
  state.SetItemsProcessed(static_cast<int64_t>(p.bodies));
  state.counters["bodies_per_frame"] = static_cast<double>(p.bodies) / static_cast<double>(frames);
  state.counters["gallery_users"] = p.gallery->user_count();
}
BENCHMARK(BM_ReidOnlineFrame)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->MinTime(5.0);

// Matching one scan against every stored scan of a gallery of range(0) users x 8 views (what a
// pending body pays per frame on top of describing its scan): through the gallery index (the online
// path, reid/gallery_index.h) ...
void BM_GallerySearch(benchmark::State& state) {
  auto matcher = make_matcher("stripes");
  Gallery gallery(make_gallery(static_cast<int>(state.range(0)), *matcher, "search"));
  cv::Mat probe_image(160, 64, CV_8UC3, cv::Scalar(40, 80, 200));
  const std::vector<float> probe = matcher->describe(PersonImage{probe_image, {}});
  const GalleryIndex index(
      gallery, *matcher, [](const GalleryEntry&) { return true; },
      [](const GalleryEntry& e) { return DescriptorView(e.features.ptr<float>(), e.features.total() - kBodyFeatures); });
  std::vector<double> sims;
  double best = -1e300;
  for (auto _ : state) {
    for (View v : kAllViews) {
      index.search(v, probe, sims);
      for (double s : sims) best = std::max(best, s);
    }
    benchmark::DoNotOptimize(best);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(index.size()));
}
BENCHMARK(BM_GallerySearch)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// ... and one stored scan at a time with the matcher's similarity() (the dense descriptors as stored).
void BM_GallerySearchPairwise(benchmark::State& state) {
  auto matcher = make_matcher("stripes");
  Gallery gallery(make_gallery(static_cast<int>(state.range(0)), *matcher, "pairwise"));
  cv::Mat probe_image(160, 64, CV_8UC3, cv::Scalar(40, 80, 200));
  const std::vector<float> probe = matcher->describe(PersonImage{probe_image, {}});
  double best = -1e300;
  for (auto _ : state) {
    for (View v : kAllViews)
      for (const GalleryEntry& e : gallery.scans(v)) {
        const float* p = e.features.ptr<float>();
        best = std::max(best, matcher->similarity(probe, DescriptorView(p, e.features.total() - kBodyFeatures)));
      }
    benchmark::DoNotOptimize(best);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0) * kViewCount);
}
BENCHMARK(BM_GallerySearchPairwise)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// The gallery file with its WAL, in MB.
double file_mb(const std::string& path) {
  double bytes = 0;
  for (const std::string& f : {path, path + "-wal"}) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(f, ec);
    if (!ec) bytes += static_cast<double>(size);
  }
  return bytes / 1e6;
}

// Soak: 50 000 frames (833 return visits of the 4 people) through orientation, scans and online
// re-identification on a 100-user gallery; resident memory after warm-up (frame 2000) and at the end,
// and what the gallery holds at the end (bounded by users x views).
void BM_ReidSoak(benchmark::State& state) {
  for (auto _ : state) {
    Pipeline p(100);
    double warm = 0;
    for (int i = 0; i < state.range(0); ++i) {
      p.step();
      if (i == 2000) warm = bench::resident_mb();
    }
    int scans = 0;
    for (const User& u : p.gallery->users()) scans += u.scans;
    state.counters["frames"] = static_cast<double>(state.range(0));
    state.counters["rss_warm_mb"] = warm;
    state.counters["rss_end_mb"] = bench::resident_mb();
    state.counters["rss_growth_pct"] = warm > 0 ? 100.0 * (bench::resident_mb() - warm) / warm : 0.0;
    state.counters["users"] = p.gallery->user_count();
    state.counters["scans"] = scans;
    state.counters["live_tracks"] = static_cast<double>(p.reid->live_tracks());
    // The event history is capped per user (GalleryOptions::max_events_per_user), so the file is
    // bounded too: events at most (users + 1) x the cap.
    state.counters["events"] = static_cast<double>(p.gallery->events().size());
    state.counters["file_mb"] = file_mb(p.gallery->path());
  }
}
BENCHMARK(BM_ReidSoak)->Arg(50000)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
