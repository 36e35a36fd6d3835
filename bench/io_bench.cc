// Reading one frame file (io/image_file.h): the checks before decoding (a PNG's chunks walked and each one's
// CRC computed, a JPEG's end marker looked for) against the whole read and decode, on a synthetic
// recording's 960x540 colour frame (PNG) and 512x424 depth frame (16-bit PNG), and the colour frame as JPEG.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/io/image_file.h"
#include "bodyrec/rgbd/synth.h"

namespace {

enum class Frame { kColourPng, kDepthPng, kColourJpeg };

// The three files, written once per process into a folder of its own (removed at exit): frame 60 of a
// 3-person walk.
struct FrameFiles {
  std::string dir;
  FrameFiles() {
    char name[] = "/tmp/bodyrec-io-bench-XXXXXX";
    if (!::mkdtemp(name)) throw std::runtime_error("io_bench: cannot create a temporary folder");
    dir = name;
    bodyrec::SynthOptions o;
    o.people = 3;
    o.frames = 120;
    o.seed = 1;
    const bodyrec::RgbdFrame frame = bodyrec::Synthesizer(o).render(60);
    cv::imwrite(dir + "/colour.png", frame.color);
    cv::imwrite(dir + "/depth.png", frame.depth);
    cv::imwrite(dir + "/colour.jpg", frame.color);
  }
  ~FrameFiles() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

std::string frame_file(Frame which) {
  static const FrameFiles files;
  const char* names[] = {"/colour.png", "/depth.png", "/colour.jpg"};
  return files.dir + names[static_cast<int>(which)];
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
