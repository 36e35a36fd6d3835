#include "bench_support.h"

#include <map>
#include <utility>

#include <opencv2/videoio.hpp>

namespace bodyrec::bench {

const std::vector<cv::Mat>& vtest_frames(int start, int count) {
  static std::map<std::pair<int, int>, std::vector<cv::Mat>> cache;
  auto& frames = cache[{start, count}];
  if (!frames.empty()) return frames;
  cv::VideoCapture capture(kVtestPath);
  cv::Mat frame;
  for (int i = 0; i < start + count && capture.read(frame); ++i)
    if (i >= start) frames.push_back(frame.clone());
  return frames;
}

}  // namespace bodyrec::bench
