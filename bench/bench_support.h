// Shared inputs for the benchmarks: frames of vtest.avi (Debian opencv-doc) decoded once into memory.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec::bench {

const std::string kVtestPath = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";

// Frames [start, start + count) of vtest.avi; empty when the video is missing.
const std::vector<cv::Mat>& vtest_frames(int start = 0, int count = 200);

// This process's resident memory now, in MiB (/proc/self/statm), for the soak benchmarks.
double resident_mb();

}  // namespace bodyrec::bench
