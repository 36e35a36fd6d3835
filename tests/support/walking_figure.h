// A static camera's image sequence with one person-like figure walking right, for tests of the commands
// that find people by background subtraction (--preset foreground, plain-camera reid).
#pragma once

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace bodyrec::testing {

// Frame f of 40, 320x240: a plain background and a 30x90 figure (red top, blue legs) whose left edge is at
// 20 + 5 f, rows 100-189.
inline cv::Mat walking_figure_frame(int f) {
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar(140, 150, 150));
  cv::rectangle(image, cv::Rect(20 + 5 * f, 100, 30, 40), cv::Scalar(40, 40, 200), cv::FILLED);
  cv::rectangle(image, cv::Rect(20 + 5 * f, 140, 30, 50), cv::Scalar(120, 30, 30), cv::FILLED);
  return image;
}

// The 40 frames as PNG files 000.png ... 039.png in `dir` (an image sequence: no frame times).
inline std::filesystem::path walking_figure(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (int f = 0; f < 40; ++f) {
    char name[16];
    std::snprintf(name, sizeof name, "%03d.png", f);
    cv::imwrite((dir / name).string(), walking_figure_frame(f));
  }
  return dir;
}

// The 40 frames as an MJPEG video at 25 fps (frame times, so walking directions give views).
inline std::filesystem::path walking_figure_video(const std::filesystem::path& path) {
  cv::VideoWriter video(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, cv::Size(320, 240));
  if (!video.isOpened()) throw std::runtime_error("cannot write the test video " + path.string());
  for (int f = 0; f < 40; ++f) video.write(walking_figure_frame(f));
  return path;
}

}  // namespace bodyrec::testing
