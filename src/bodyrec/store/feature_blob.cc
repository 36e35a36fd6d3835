#include "bodyrec/store/feature_blob.h"

#include <cstdint>
#include <cstring>

#include "bodyrec/core/error.h"

namespace bodyrec::store {

namespace {
constexpr char kMagic[4] = {'B', 'R', 'F', '1'};
constexpr size_t kHeader = 16;
}  // namespace

std::vector<unsigned char> encode_features(const cv::Mat& features) {
  const cv::Mat m = features.isContinuous() ? features : features.clone();
  const int32_t header[3] = {m.type(), m.rows, m.cols};
  const size_t bytes = m.total() * m.elemSize();
  std::vector<unsigned char> blob(kHeader + bytes);
  std::memcpy(blob.data(), kMagic, 4);
  std::memcpy(blob.data() + 4, header, sizeof(header));
  if (bytes) std::memcpy(blob.data() + kHeader, m.data, bytes);
  return blob;
}

cv::Mat decode_features(const unsigned char* data, size_t size, const std::string& where) {
  int32_t header[3] = {0, 0, 0};
  if (size < kHeader || std::memcmp(data, kMagic, 4) != 0)
    throw InputError(where + ": corrupt features blob (no BRF1 header)");
  std::memcpy(header, data + 4, sizeof(header));
  const int type = header[0], rows = header[1], cols = header[2];
  if (rows < 0 || cols < 0 || CV_MAT_DEPTH(type) > CV_16F || (type & ~CV_MAT_TYPE_MASK) != 0)
    throw InputError(where + ": corrupt features blob (bad type or size)");
  const size_t expected = static_cast<size_t>(rows) * static_cast<size_t>(cols) * CV_ELEM_SIZE(type);
  if (expected != size - kHeader)
    throw InputError(where + ": corrupt features blob (" + std::to_string(size - kHeader) + " bytes for " +
                     std::to_string(rows) + "x" + std::to_string(cols) + ")");
  cv::Mat m(rows, cols, type);
  if (expected) std::memcpy(m.data, data + kHeader, expected);
  return m;
}

cv::Mat decode_features(const std::vector<unsigned char>& blob, const std::string& where) {
  return decode_features(blob.data(), blob.size(), where);
}

}  // namespace bodyrec::store
