// How a feature matrix (any cv::Mat) is stored in the gallery's `features` column: the 16-byte header
// "BRF1", type, rows, cols (int32, little-endian as on every machine bodyrec runs on), then the
// continuous data. The descriptor name/version beside it say what the numbers mean.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec::store {

std::vector<unsigned char> encode_features(const cv::Mat& features);
// Throws InputError "<where>: corrupt features blob" when the header or size does not match.
cv::Mat decode_features(const std::vector<unsigned char>& blob, const std::string& where);
cv::Mat decode_features(const unsigned char* data, size_t size, const std::string& where);

}  // namespace bodyrec::store
