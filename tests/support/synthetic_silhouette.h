// Drawn people for tests that need masks and images with known outlines: a head, a torso, two legs and
// two arms whose sizes and angles vary with a seed, on a textured background.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_support.h"

namespace bodyrec::testing {

struct Silhouette {
  cv::Mat image;  // BGR
  cv::Mat mask;   // CV_8U, `value` on the person, 0 elsewhere
};

// Draws one person of about `height` px whose head top is near `top_center` into `mask` (as `value`) and
// `image`. Deterministic for a given seed.
inline void draw_person(cv::Mat& image, cv::Mat& mask, cv::Point top_center, int height, uint64_t seed,
                        uchar value = 255) {
  cv::RNG rng(seed);
  cv::Mat person = cv::Mat::zeros(mask.size(), CV_8U);
  const double u = height / 100.0;  // body unit
  const int head_r = cvRound((6.5 + rng.uniform(-1.0, 1.0)) * u);
  const cv::Point head(top_center.x, top_center.y + head_r);
  cv::circle(person, head, head_r, 255, cv::FILLED);
  const int shoulder_y = head.y + head_r + cvRound(2 * u);
  const int half_width = cvRound((9 + rng.uniform(-2.0, 2.0)) * u);
  const int hip_y = shoulder_y + cvRound((32 + rng.uniform(-3.0, 3.0)) * u);
  cv::rectangle(person, cv::Point(head.x - cvRound(2.5 * u), head.y), cv::Point(head.x + cvRound(2.5 * u), shoulder_y),
                255, cv::FILLED);  // neck
  cv::rectangle(person, cv::Point(head.x - half_width, shoulder_y), cv::Point(head.x + half_width, hip_y), 255,
                cv::FILLED);
  const int bottom = top_center.y + height - 1;
  const int limb = std::max(2, cvRound(5 * u));
  for (int side : {-1, 1}) {
    const double spread = rng.uniform(0.0, 12.0) * u;
    cv::line(person, cv::Point(head.x + side * cvRound(half_width * 0.5), hip_y),
             cv::Point(head.x + side * cvRound(half_width * 0.5 + spread), bottom - limb), 255, 2 * limb);
    const double angle = rng.uniform(0.15, 0.7);  // from hanging down
    const double length = 30 * u;
    const cv::Point shoulder(head.x + side * (half_width - limb), shoulder_y + limb);
    cv::line(person, shoulder,
             shoulder + cv::Point(cvRound(side * length * std::sin(angle)), cvRound(length * std::cos(angle))), 255,
             2 * limb);
  }
  mask.setTo(value, person);
  const cv::Scalar color(rng.uniform(150, 230), rng.uniform(150, 230), rng.uniform(150, 230));
  image.setTo(color, person);
}

// A textured background of `size` with one person of `height` px centred horizontally.
inline Silhouette make_silhouette(cv::Size size, int height, uint64_t seed) {
  Silhouette s;
  cv::RNG rng(seed * 7919 + 1);
  s.image.create(size, CV_8UC3);
  rng.fill(s.image, cv::RNG::UNIFORM, cv::Scalar::all(20), cv::Scalar::all(90));
  cv::GaussianBlur(s.image, s.image, cv::Size(5, 5), 0);
  s.mask = cv::Mat::zeros(size, CV_8U);
  const int x = size.width / 2 + rng.uniform(-size.width / 10, size.width / 10 + 1);
  const int y = (size.height - height) / 2 + rng.uniform(-5, 6);
  draw_person(s.image, s.mask, cv::Point(x, y), height, seed, 1);
  return s;
}

// A Penn-Fudan-like folder (PNGImages/, PedMasks/, Annotation/) of eight 240x200 images P00..P07
// (P03 and P07 are the test split): each has a 150 px person (mask value 1); P01 and P05 also a 60 px
// person (too small, value 2); P02 also one cut by the left border (value 2).
inline void make_pennfudan_like(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  fs::create_directories(root / "PNGImages");
  fs::create_directories(root / "PedMasks");
  fs::create_directories(root / "Annotation");
  for (int i = 0; i < 8; ++i) {
    const std::string stem = "P0" + std::to_string(i);
    auto s = make_silhouette(cv::Size(240, 200), 150, static_cast<uint64_t>(i + 1));
    std::vector<cv::Rect> boxes = {cv::boundingRect(s.mask)};
    if (i == 1 || i == 5) {
      draw_person(s.image, s.mask, cv::Point(25, 20), 60, 50, 2);
      boxes.push_back(cv::boundingRect(s.mask == 2));
    }
    if (i == 2) {
      draw_person(s.image, s.mask, cv::Point(8, 10), 180, 60, 2);
      s.mask.colRange(0, 15).setTo(2, s.mask.colRange(0, 15) == 0);  // a wide cut along the left border
      boxes.push_back(cv::boundingRect(s.mask == 2));
    }
    cv::imwrite((root / "PNGImages" / (stem + ".png")).string(), s.image);
    cv::imwrite((root / "PedMasks" / (stem + "_mask.png")).string(), s.mask);
    std::string text = "# Compatible with PASCAL Annotation Version 1.00\n";
    for (size_t k = 0; k < boxes.size(); ++k) {
      const cv::Rect& r = boxes[k];
      text += "Bounding box for object " + std::to_string(k + 1) +
              " \"PASpersonWalking\" (Xmin, Ymin) - (Xmax, Ymax) : (" + std::to_string(r.x + 1) + ", " +
              std::to_string(r.y + 1) + ") - (" + std::to_string(r.x + r.width) + ", " +
              std::to_string(r.y + r.height) + ")\n";
    }
    write_text(root / "Annotation" / (stem + ".txt"), text);
  }
}

}  // namespace bodyrec::testing
