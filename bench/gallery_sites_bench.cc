// The gallery on SQLite against PostgreSQL (issue 47), at 1 000 and 10 000 users of 4 views each with
// stripes-sized features (1 x 1410 floats, 5.6 KB): what enrolment and recognition cost on the gallery
// side. put_scan (a better scan with its 128 x 64 image and mask: one write transaction), log_event (one
// `recognised` event: one write transaction with the event-cap trim), refresh when nothing changed (what
// reid does every frame), refresh after another connection logged an event (nothing to reload) or stored
// a better scan (the whole feature cache is read again), open (connect, schema check, feature cache load), and forget (delete + scrub: SQLite
// VACUUM + WAL checkpoint; PostgreSQL VACUUM FULL + CHECKPOINT), and an enrolment under the write lock as reid
// makes it (BM_LockedEnrol).
//
// Args: {backend (0 SQLite, 1 PostgreSQL), users}. SQLite files live in the system temp directory;
// PostgreSQL is a private durable server (fsync on, Unix socket, tests/support/server_fixtures.h) on the same
// disk, so both pay an fsync per commit. The fixture galleries are built once per process (minutes for
// 10 000 users on PostgreSQL: one round trip per statement).
#include <filesystem>
#include <map>
#include <random>

#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/store/gallery.h"
#include "server_fixtures.h"

namespace {

namespace fs = std::filesystem;
using namespace bodyrec;

constexpr int kViews = 4;
const View kFixtureViews[kViews] = {View::F, View::SL, View::B, View::SR};

// A person-sized scan: a smooth random image (as compressible as a real body, 5-10 KB of PNG), an
// elliptic mask and stripes-sized features.
GalleryScan scan(View view, double quality, int seed) {
  cv::RNG rng(static_cast<uint64_t>(seed) * 7919 + 13);
  cv::Mat coarse(8, 4, CV_8UC3);
  rng.fill(coarse, cv::RNG::UNIFORM, 0, 256);
  GalleryScan s;
  s.view = view;
  cv::resize(coarse, s.image, cv::Size(64, 128), 0, 0, cv::INTER_LINEAR);
  s.mask = cv::Mat::zeros(128, 64, CV_8UC1);
  cv::ellipse(s.mask, cv::Point(32, 64), cv::Size(28, 60), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  s.features = cv::Mat(1, 1410, CV_32F);
  rng.fill(s.features, cv::RNG::UNIFORM, 0.0, 1.0);
  s.descriptor = "stripes2";
  s.descriptor_version = 2;
  s.quality = quality;
  return s;
}

struct Place {
  fs::path dir;
  std::unique_ptr<testing::PostgresServer> pg;
  std::string pg_error;
  std::map<std::pair<int, int>, std::string> galleries;  // (backend, users) -> location
  int databases = 0;

  Place() {
    dir = fs::temp_directory_path() / ("bodyrec-sites-bench-" + std::to_string(std::random_device()()));
    fs::create_directories(dir);
  }
  ~Place() {
    pg.reset();
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  // A new empty gallery location of `backend`; "" when PostgreSQL is not available.
  std::string fresh(int backend) {
    if (backend == 0) return (dir / ("g" + std::to_string(++databases) + ".db")).string();
    if (!pg && pg_error.empty()) {
      pg = testing::PostgresServer::make(true, &pg_error);
      if (!pg && pg_error.empty()) pg_error = "no PostgreSQL";
    }
    return pg ? pg->create_database("bench") : "";
  }
  // users x kViews scans, features only (loading and searching never read pixels), built once.
  std::string gallery(int backend, int users) {
    auto& location = galleries[{backend, users}];
    if (!location.empty()) return location;
    location = fresh(backend);
    if (location.empty()) return location;
    GalleryOptions o;
    o.create = true;
    o.store_images = false;
    o.sync_full = false;  // building the fixture only
    Gallery g(location, o);
    g.transaction([&] {
      for (int u = 0; u < users; ++u) {
        const UserId id = g.enrol(scan(kFixtureViews[0], 0.5, u * kViews));
        for (int v = 1; v < kViews; ++v) g.put_scan(id, scan(kFixtureViews[v], 0.5, u * kViews + v));
      }
    });
    return location;
  }
};

Place& place() {
  static Place p;
  return p;
}

bool available(benchmark::State& state, const std::string& location) {
  if (!location.empty()) return true;
  state.SkipWithError(("PostgreSQL: " + place().pg_error).c_str());
  return false;
}

void BM_PutScan(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  Gallery g(location);
  std::vector<GalleryScan> scans;
  for (int i = 0; i < 16; ++i) scans.push_back(scan(View::FR, 0, 1000000 + i));
  double quality = 1;
  int i = 0;
  for (auto _ : state) {
    GalleryScan& s = scans[static_cast<size_t>(i++ % 16)];
    s.quality = quality += 1;  // always better: a replacing write with pixels
    benchmark::DoNotOptimize(g.put_scan(7, s));
  }
}

void BM_LogEvent(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  Gallery g(location);
  Event e;
  e.kind = EventKind::kRecognised;
  e.view = View::F;
  e.score = 0.5;
  int i = 0;
  const int users = static_cast<int>(state.range(1));
  for (auto _ : state) {
    e.user = 1 + (i++ * 7919) % users;
    benchmark::DoNotOptimize(g.log_event(e));
  }
}

void BM_RefreshUnchanged(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  Gallery g(location);
  for (auto _ : state) benchmark::DoNotOptimize(g.refresh());
}

void BM_RefreshAfterAnotherWrite(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  Gallery g(location), other(location);
  Event e;
  e.user = 1;
  e.kind = EventKind::kLeft;
  const bool scans = state.range(2) != 0;
  GalleryScan s = scan(View::BR, 0, 3000000);
  int reloads = 0;
  for (auto _ : state) {
    state.PauseTiming();
    if (scans) {
      s.quality += 1;  // a better scan: the cache must be reloaded
      other.put_scan(1, s);
    } else {
      other.log_event(e);  // an event: the cache stays
    }
    state.ResumeTiming();
    reloads += g.refresh();
  }
  state.counters["reloads"] = reloads;
}

void BM_Open(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  size_t entries = 0;
  for (auto _ : state) {
    Gallery g(location);
    entries = 0;
    for (View v : kFixtureViews) entries += g.scans(v).size();
  }
  state.counters["scans"] = static_cast<double>(entries);
}

// On a gallery of its own per size (the erasures change it): one user's 4 scans with pixels, then the scrub.
void BM_Forget(benchmark::State& state) {
  const int backend = static_cast<int>(state.range(0)), users = static_cast<int>(state.range(1));
  const std::string location = place().gallery(backend, users);
  if (!available(state, location)) return;
  Gallery g(location);
  for (auto _ : state) {
    state.PauseTiming();
    const UserId u = g.enrol(scan(View::F, 0.5, 2000000));
    for (int v = 1; v < kViews; ++v) g.put_scan(u, scan(kFixtureViews[v], 0.5, 2000000 + v));
    state.ResumeTiming();
    const EraseReport r = g.forget(u);
    if (!r.scrubbed) state.SkipWithError(r.note.c_str());
  }
}

// An enrolment as reid makes it (issue 47.2): under the gallery's write lock (GalleryReidStore::exclusive), take
// in others' writes (refresh: here nothing changed), then the user with 4 views (with pixels) and its event.
// Recognition costs the gallery one log_event (BM_LogEvent); matching reads the in-memory cache, the same on
// both databases (reid_online_bench). Each iteration adds a user to the fixture gallery.
void BM_LockedEnrol(benchmark::State& state) {
  const std::string location = place().gallery(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!available(state, location)) return;
  Gallery g(location);
  const auto matcher = make_matcher("stripes");
  GalleryReidStore store(g, *matcher);
  std::vector<GalleryScan> scans;
  for (int v = 0; v < kViews; ++v) scans.push_back(scan(kFixtureViews[v], 0.5, 4000000 + v));
  uint64_t track = 0;
  for (auto _ : state)
    store.exclusive([&] {
      store.refresh();
      benchmark::DoNotOptimize(store.enrol(scans, ++track, 0.0));
    });
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int backend : {0, 1})
    for (int users : {1000, 10000}) b->Args({backend, users});
  b->ArgNames({"pg", "users"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_PutScan)->Apply(sizes);
BENCHMARK(BM_LogEvent)->Apply(sizes);
BENCHMARK(BM_RefreshUnchanged)->Apply(sizes);
// Third arg: the other connection logs an event (0) or stores a better scan (1).
BENCHMARK(BM_RefreshAfterAnotherWrite)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int backend : {0, 1})
        for (int users : {1000, 10000})
          for (int scans : {0, 1}) b->Args({backend, users, scans});
      b->ArgNames({"pg", "users", "scan"})->Unit(benchmark::kMillisecond);
    })
    ->Iterations(20);
BENCHMARK(BM_Open)->Apply(sizes)->Iterations(5);
BENCHMARK(BM_Forget)->Apply(sizes)->Iterations(3);
BENCHMARK(BM_LockedEnrol)->Apply(sizes)->Iterations(50);

}  // namespace

BENCHMARK_MAIN();
