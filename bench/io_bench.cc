// Reading one frame file (io/image_file.h): the checks before decoding (a PNG's chunks walked and each one's
// CRC computed, a JPEG's end marker looked for) against the whole read and decode, on a synthetic
// recording's 960x540 colour frame (PNG) and 512x424 depth frame (16-bit PNG), and the colour frame as JPEG.
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/io/image_file.h"
#include "bodyrec/rgbd/synth.h"

namespace {

enum class Frame { kColourPng, kDepthPng, kColourJpeg };

// A file written once per process: frame 60 of a 3-person walk.
std::string frame_file(Frame which) {
  static const bodyrec::RgbdFrame frame = [] {
    bodyrec::SynthOptions o;
    o.people = 3;
    o.frames = 120;
    o.seed = 1;
    return bodyrec::Synthesizer(o).render(60);
  }();
  const char* names[] = {"/tmp/bodyrec-io-bench-colour.png", "/tmp/bodyrec-io-bench-depth.png",
                         "/tmp/bodyrec-io-bench-colour.jpg"};
  const std::string path = names[static_cast<int>(which)];
  cv::imwrite(path, which == Frame::kDepthPng ? frame.depth : frame.color);
  return path;
}

void BM_CheckBeforeDecoding(benchmark::State& state, Frame which) {
  std::ifstream in(frame_file(which), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::broken_image_reason(bytes));
  state.counters["bytes"] = static_cast<double>(bytes.size());
}

void BM_ReadImageFile(benchmark::State& state, Frame which) {
  const std::string path = frame_file(which);
  for (auto _ : state) benchmark::DoNotOptimize(bodyrec::read_image_file(path, cv::IMREAD_UNCHANGED));
}

BENCHMARK_CAPTURE(BM_CheckBeforeDecoding, colour_png, Frame::kColourPng)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CheckBeforeDecoding, depth_png, Frame::kDepthPng)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CheckBeforeDecoding, colour_jpeg, Frame::kColourJpeg)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReadImageFile, colour_png, Frame::kColourPng)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReadImageFile, depth_png, Frame::kDepthPng)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReadImageFile, colour_jpeg, Frame::kColourJpeg)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
