#include "bench_support.h"

#include <unistd.h>

#include <fstream>
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

double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

}  // namespace bodyrec::bench
