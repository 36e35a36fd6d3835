// Synthetic bodies for the online re-identification tests: a person of two colours (shirt, trousers) seen in
// one view, with a little noise per frame, as a ReidBody with its partial scan.
#pragma once

#include <opencv2/imgproc.hpp>

#include "bodyrec/reid/online_reid.h"

namespace bodyrec::testing {

// A person seen in one view: shirt and trousers of their colours, a little noise per frame.
inline PartialScan scan_of(const cv::Scalar& shirt, const cv::Scalar& trousers, View view, int frame, double quality = 0.8) {
  PartialScan s;
  s.image = cv::Mat(200, 80, CV_8UC3, cv::Scalar(0, 0, 0));
  s.mask = cv::Mat(200, 80, CV_8U, cv::Scalar(0));
  cv::circle(s.image, {40, 18}, 14, cv::Scalar(90, 120, 170), cv::FILLED);
  cv::rectangle(s.image, cv::Rect(15, 34, 50, 70), shirt, cv::FILLED);
  cv::rectangle(s.image, cv::Rect(20, 104, 40, 92), trousers, cv::FILLED);
  cv::Mat grey;
  cv::cvtColor(s.image, grey, cv::COLOR_BGR2GRAY);
  s.mask = grey > 0;
  cv::Mat noise(s.image.size(), CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(frame + 1));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
  cv::add(s.image, noise, s.image, s.mask);
  s.box = cv::Rect(100, 50, 80, 200);
  s.pixels = cv::countNonZero(s.mask);
  s.completeness = s.sharpness = s.resolution = 1;
  s.quality = quality;
  s.view.view = view;
  s.view.confidence = 0.9;
  return s;
}

inline const cv::Scalar kRed(30, 30, 210), kBlue(160, 60, 20), kGreen(40, 180, 40), kYellow(30, 210, 220);

inline ReidBody body(uint64_t track, const cv::Scalar& shirt, const cv::Scalar& trousers, View view, int frame,
              double quality = 0.8) {
  ReidBody b;
  b.track = track;
  b.view.view = view;
  b.view.confidence = 0.9;
  b.scan = scan_of(shirt, trousers, view, frame, quality);
  b.box = b.scan->box;
  return b;
}

}  // namespace bodyrec::testing
