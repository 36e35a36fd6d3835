// Depth-only people segmentation and the CCD contour per 512x424 frame (issue 5 targets: segmentation
// <= 15 ms, background removal + CCD contour <= 2 ms). Frames are rendered beforehand by the synthesizer
// (seed 1, walk-turn, 150 frames, frames 60-89 timed); the segmenter's background is learnt from 60
// frames spread over the same recording, as `bodyrec segment` does. Also the real PCL five_people frame (640x480,
// ground plane only) when BODYREC_DATA / ../shared/datasets has it.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include <benchmark/benchmark.h>

#include "bodyrec/rgbd/contour.h"
#include "bodyrec/rgbd/green_screen.h"
#include "bodyrec/rgbd/pcd.h"
#include "bodyrec/rgbd/segment.h"
#include "bodyrec/rgbd/synth.h"

namespace {

struct SynthFrames {
  std::unique_ptr<bodyrec::Synthesizer> synth;
  std::vector<bodyrec::RgbdFrame> frames;
  std::vector<cv::Mat> background;
};

const SynthFrames& synth_frames(int people) {
  static std::map<int, SynthFrames> cache;
  SynthFrames& s = cache[people];
  if (!s.frames.empty()) return s;
  bodyrec::SynthOptions o;
  o.people = people;
  o.frames = 150;
  o.seed = 1;
  s.synth = std::make_unique<bodyrec::Synthesizer>(o);
  // As learn_recording_background: 60 frames spread evenly over the recording.
  for (int k = 0; k < 60; ++k) s.background.push_back(s.synth->render(k * o.frames / 60).depth.clone());
  for (int i = 60; i < 90; ++i) {
    bodyrec::RgbdFrame f = s.synth->render(i);
    f.depth = f.depth.clone();
    f.body_index = f.body_index.clone();
    f.color = f.color.clone();
    s.frames.push_back(std::move(f));
  }
  return s;
}

void BM_DepthSegment(benchmark::State& state) {
  const SynthFrames& s = synth_frames(static_cast<int>(state.range(0)));
  bodyrec::DepthSegmenter seg(s.synth->meta().depth, s.synth->meta().depth_unit_m);
  for (const auto& d : s.background) seg.learn_background(d);
  size_t i = 0, people = 0;
  for (auto _ : state) {
    people += seg.segment(s.frames[i].depth).people.size();
    i = (i + 1) % s.frames.size();
  }
  state.counters["people_per_frame"] = static_cast<double>(people) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_DepthSegment)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DepthSegmentPclFrame(benchmark::State& state) {
  const char* env = std::getenv("BODYREC_DATA");
  const std::filesystem::path file =
      std::filesystem::path(env ? env : "../shared/datasets") / "pcl_people_rgbd" / "five_people.pcd";
  if (!std::filesystem::exists(file)) {
    state.SkipWithError("five_people.pcd not found (set BODYREC_DATA)");
    return;
  }
  const bodyrec::PcdCloud cloud = bodyrec::read_pcd(file.string());
  const bodyrec::Intrinsics k = bodyrec::fit_pcd_intrinsics(cloud, file.string());
  cv::Mat depth(cloud.height, cloud.width, CV_16U, cv::Scalar(0));
  for (int v = 0; v < cloud.height; ++v)
    for (int u = 0; u < cloud.width; ++u) {
      const float z = cloud.xyz.at<cv::Vec3f>(v, u)[2];
      if (std::isfinite(z)) depth.at<uint16_t>(v, u) = static_cast<uint16_t>(std::lround(z * 1000));
    }
  bodyrec::DepthSegmenter seg(k, 0.001);
  size_t people = 0;
  for (auto _ : state) people += seg.segment(depth).people.size();
  state.counters["people_per_frame"] = static_cast<double>(people) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_DepthSegmentPclFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

// Thesis Ch5 per frame: background removal into per-body BGRA images, then the CCD cross test.
void BM_BackgroundRemovalAndCcd(benchmark::State& state) {
  const SynthFrames& s = synth_frames(2);
  bodyrec::BackgroundRemoval removal(s.synth->meta());
  std::array<cv::Mat, bodyrec::kMaxBodies> cutouts;
  cv::Mat contour;
  size_t i = 0;
  for (auto _ : state) {
    const auto& f = s.frames[i];
    removal.apply(f.depth, f.body_index, f.color, cutouts);
    bodyrec::ccd_contour(f.body_index, contour);
    benchmark::DoNotOptimize(contour.data);
    i = (i + 1) % s.frames.size();
  }
}
BENCHMARK(BM_BackgroundRemovalAndCcd)->Unit(benchmark::kMillisecond)->UseRealTime();

// The CCD cross test alone, and ordered outlines + 180 landmarks with 3D points per body (both methods).
void BM_CcdKernel(benchmark::State& state) {
  const SynthFrames& s = synth_frames(2);
  cv::Mat contour;
  size_t i = 0;
  for (auto _ : state) {
    bodyrec::ccd_contour(s.frames[i].body_index, contour);
    i = (i + 1) % s.frames.size();
  }
}
BENCHMARK(BM_CcdKernel)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ContourLandmarks(benchmark::State& state) {
  const SynthFrames& s = synth_frames(2);
  const auto method = state.range(0) ? bodyrec::ContourMethod::kOpenCv : bodyrec::ContourMethod::kCcd;
  size_t i = 0;
  for (auto _ : state) {
    const auto& f = s.frames[i];
    benchmark::DoNotOptimize(bodyrec::body_contours(f.body_index, f.depth, s.synth->meta().depth, 0.001, 180, method));
    i = (i + 1) % s.frames.size();
  }
  state.SetLabel(state.range(0) ? "opencv" : "ccd");
}
BENCHMARK(BM_ContourLandmarks)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
BENCHMARK_MAIN();
