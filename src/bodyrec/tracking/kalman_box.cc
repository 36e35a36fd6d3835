#include "bodyrec/tracking/kalman_box.h"

#include <algorithm>

namespace bodyrec {
namespace {

cv::Mat measurement_of(const Box& b) {
  return (cv::Mat_<double>(4, 1) << b.x + b.width / 2, b.y + b.height / 2, b.width, b.height);
}

}  // namespace

KalmanBoxFilter::KalmanBoxFilter(const Box& box, const KalmanNoise& noise) : kf_(8, 4, 0, CV_64F), noise_(noise) {
  kf_.transitionMatrix = cv::Mat::eye(8, 8, CV_64F);
  for (int i = 0; i < 4; ++i) kf_.transitionMatrix.at<double>(i, i + 4) = 1.0;  // x += v per frame
  kf_.measurementMatrix = cv::Mat::zeros(4, 8, CV_64F);
  for (int i = 0; i < 4; ++i) kf_.measurementMatrix.at<double>(i, i) = 1.0;
  kf_.statePost = cv::Mat::zeros(8, 1, CV_64F);
  measurement_of(box).copyTo(kf_.statePost.rowRange(0, 4));
  const double h = std::max(box.height, 1.0);
  kf_.errorCovPost = cv::Mat::zeros(8, 8, CV_64F);
  for (int i = 0; i < 4; ++i) {
    const double p = 2 * noise_.position * h, v = 10 * noise_.velocity * h;
    kf_.errorCovPost.at<double>(i, i) = p * p;
    kf_.errorCovPost.at<double>(i + 4, i + 4) = v * v;
  }
  set_noise(h);
  kf_.statePost.copyTo(kf_.statePre);  // so that correct() before any predict() starts from `box`
  kf_.errorCovPost.copyTo(kf_.errorCovPre);
}

void KalmanBoxFilter::set_noise(double height) {
  const double h = std::max(height, 1.0);
  kf_.processNoiseCov = cv::Mat::zeros(8, 8, CV_64F);
  kf_.measurementNoiseCov = cv::Mat::zeros(4, 4, CV_64F);
  for (int i = 0; i < 4; ++i) {
    const double p = noise_.position * h, v = noise_.velocity * h, m = noise_.measurement * h;
    kf_.processNoiseCov.at<double>(i, i) = p * p;
    kf_.processNoiseCov.at<double>(i + 4, i + 4) = v * v;
    kf_.measurementNoiseCov.at<double>(i, i) = m * m;
  }
}

void KalmanBoxFilter::predict(int frames) {
  for (int i = 0; i < frames; ++i) {
    set_noise(kf_.statePost.at<double>(3));
    kf_.predict();  // also copies the prediction into statePost, so predictions chain
    for (int k = 2; k < 4; ++k) {
      if (kf_.statePost.at<double>(k) >= 1.0) continue;
      for (cv::Mat* s : {&kf_.statePre, &kf_.statePost}) {  // correct() starts from statePre
        s->at<double>(k) = 1.0;
        s->at<double>(k + 4) = 0.0;
      }
    }
  }
}

void KalmanBoxFilter::correct(const Box& box) {
  set_noise(box.height);
  kf_.correct(measurement_of(box));
}

Box KalmanBoxFilter::box() const {
  const cv::Mat& s = kf_.statePost;
  const double w = std::max(s.at<double>(2), 1.0), h = std::max(s.at<double>(3), 1.0);
  return Box(s.at<double>(0) - w / 2, s.at<double>(1) - h / 2, w, h);
}

cv::Point2d KalmanBoxFilter::velocity() const {
  return {kf_.statePost.at<double>(4), kf_.statePost.at<double>(5)};
}

}  // namespace bodyrec
