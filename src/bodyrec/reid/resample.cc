#include "bodyrec/reid/resample.h"

#include <opencv2/imgproc.hpp>

namespace bodyrec {

cv::Mat resample_image(const cv::Mat& image, cv::Size size) {
  CV_Assert(!image.empty() && size.width > 0 && size.height > 0);
  if (image.size() == size) return image;
  const bool grows = size.width > image.cols || size.height > image.rows;
  cv::Mat out;
  cv::resize(image, out, size, 0, 0, grows ? cv::INTER_LINEAR : cv::INTER_AREA);
  return out;
}

cv::Mat resample_mask(const cv::Mat& mask, cv::Size size) {
  CV_Assert(!mask.empty() && size.width > 0 && size.height > 0);
  if (mask.size() == size) return mask;
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_NEAREST);
  return out;
}

}  // namespace bodyrec
