#include "bodyrec/reid/kaze_matcher.h"

#include <opencv2/features2d.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

cv::Mat kaze_descriptors(const PersonImage& image) {
  CV_Assert(!image.bgr.empty());
  static thread_local cv::Ptr<cv::KAZE> kaze = cv::KAZE::create();
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  kaze->detectAndCompute(image.bgr, image.mask, keypoints,  // an empty mask means the whole image
                         descriptors);
  if (descriptors.empty()) return cv::Mat(0, 64, CV_32F);
  return descriptors;
}

int kaze_score(const cv::Mat& probe_descriptors, const cv::Mat& gallery_descriptors) {
  if (probe_descriptors.rows < 1 || gallery_descriptors.rows < 2) return 0;
  cv::FlannBasedMatcher matcher;  // k-d tree index (4 randomised trees), as FLANN's KDTreeIndexParams
  matcher.add(gallery_descriptors);
  matcher.train();
  std::vector<std::vector<cv::DMatch>> knn;  // fresh every call: knnMatch appends in OpenCV 4.6
  matcher.knnMatch(probe_descriptors, knn, 2);
  int kept = 0;
  for (const auto& m : knn)
    if (m.size() >= 2 && m[0].distance <= kKazeRatio * m[1].distance) ++kept;
  return 2 * kept;
}

std::vector<float> pack_descriptors(const cv::Mat& descriptors) {
  CV_Assert(descriptors.empty() || descriptors.type() == CV_32F);
  std::vector<float> packed = {static_cast<float>(descriptors.rows), static_cast<float>(descriptors.cols)};
  for (int r = 0; r < descriptors.rows; ++r)
    packed.insert(packed.end(), descriptors.ptr<float>(r), descriptors.ptr<float>(r) + descriptors.cols);
  return packed;
}

cv::Mat unpack_descriptors(const std::vector<float>& packed) {
  if (packed.size() < 2) throw InputError("KAZE descriptor blob: shorter than its header");
  const int rows = static_cast<int>(packed[0]), cols = static_cast<int>(packed[1]);
  if (rows < 0 || cols < 0 || packed.size() != 2 + size_t(rows) * size_t(cols))
    throw InputError("KAZE descriptor blob: size does not match its header");
  cv::Mat m(rows, cols, CV_32F);
  if (rows > 0 && cols > 0) std::copy(packed.begin() + 2, packed.end(), m.ptr<float>());
  return m;
}

}  // namespace bodyrec
