// The whole group-leader pipeline per frame on vtest.avi (768x576), as `bodyrec groups` runs it by default:
// HOG detection (default preset, motion regions; every 2nd frame, searches near the tracks in between)
// -> Kalman/Hungarian tracking -> three-frame motion ->
// trajectory groups on the PETS ground plane -> roles -> DSST leader tracking -> Farneback direction.
// Frames are decoded before timing and fed in video order, cycling over 300 frames (the frame counter
// keeps increasing, so the trackers see one long video with a jump every 300 frames). Real time per
// iteration = time per frame. BM_GroupStagesOnly leaves detection and tracking out (tracks recorded
// from a first pass), to show what the Ch4 stages themselves cost.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bench_support.h"
#include "bodyrec/detection/hog_people_detector.h"
#include "bodyrec/groups/group_stages.h"
#include "bodyrec/io/ground_plane.h"
#include "bodyrec/tracking/detect_and_track.h"

namespace {

constexpr double kFps = 7.0;  // PETS 2009 S2.L1's recording rate

std::shared_ptr<const bodyrec::GroundPlane> pets_ground() {
  const char* env = std::getenv("BODYREC_DATA");
  const std::filesystem::path path =
      std::filesystem::path(env && *env ? env : "../shared/datasets") / "pets09_s2l1" / "View_001.xml";
  if (!std::filesystem::exists(path)) return nullptr;  // pixels then; same cost
  return bodyrec::read_tsai_calibration(path.string());
}

// The 300 frames, or nullptr after marking the benchmark skipped.
const std::vector<cv::Mat>* frames_or_skip(benchmark::State& state) {
  const auto& frames = bodyrec::bench::vtest_frames(0, 300);
  if (!frames.empty()) return &frames;
  state.SkipWithError("vtest.avi not found (install opencv-doc: scripts/install-deps)");
  return nullptr;
}

void BM_GroupsPipeline(benchmark::State& state) {
  const auto* loaded = frames_or_skip(state);
  if (!loaded) return;
  const auto& frames = *loaded;
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kDefault));
  bodyrec::DetectAndTrack tracking(detector, {});
  bodyrec::GroupStages pipeline({}, pets_ground());
  int n = 0;
  double leaders = 0;
  for (auto _ : state) {
    const cv::Mat& frame = frames[static_cast<size_t>(n) % frames.size()];
    auto tracks = tracking.step(n, frame);
    leaders += static_cast<double>(pipeline.process(frame, n / kFps, tracks).leaders.size());
    ++n;
  }
  state.counters["leaders_per_frame"] = leaders / static_cast<double>(state.iterations());
}

void BM_GroupStagesOnly(benchmark::State& state) {
  const auto* loaded = frames_or_skip(state);
  if (!loaded) return;
  const auto& frames = *loaded;
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kDefault));
  bodyrec::DetectAndTrack tracking(detector, {});
  std::vector<std::vector<bodyrec::TrackedPerson>> tracks;
  for (size_t i = 0; i < frames.size(); ++i) tracks.push_back(tracking.step(static_cast<int>(i), frames[i]));
  bodyrec::GroupStages pipeline({}, pets_ground());
  int n = 0;
  for (auto _ : state) {
    const size_t i = static_cast<size_t>(n) % frames.size();
    benchmark::DoNotOptimize(pipeline.process(frames[i], n / kFps, tracks[i]));
    ++n;
  }
}

// Soak: range(0) frames (the 300 decoded frames cycled; 8000 is ten times the video's length) through
// the whole pipeline; resident memory after warm-up (frame 500) and at the end.
void BM_GroupsSoak(benchmark::State& state) {
  const auto* loaded = frames_or_skip(state);
  if (!loaded) return;
  const auto& frames = *loaded;
  for (auto _ : state) {
    bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kDefault));
    bodyrec::DetectAndTrack tracking(detector, {});
    bodyrec::GroupStages pipeline({}, pets_ground());
    double warm = 0;
    for (int n = 0; n < state.range(0); ++n) {
      const cv::Mat& frame = frames[static_cast<size_t>(n) % frames.size()];
      pipeline.process(frame, n / kFps, tracking.step(n, frame));
      if (n == 500) warm = bodyrec::bench::resident_mb();
    }
    const double end = bodyrec::bench::resident_mb();
    state.counters["frames"] = static_cast<double>(state.range(0));
    state.counters["rss_warm_mb"] = warm;
    state.counters["rss_end_mb"] = end;
    state.counters["rss_growth_pct"] = warm > 0 ? 100.0 * (end - warm) / warm : 0.0;
  }
}

BENCHMARK(BM_GroupsPipeline)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(10.0);
BENCHMARK(BM_GroupStagesOnly)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK(BM_GroupsSoak)->Arg(8000)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
