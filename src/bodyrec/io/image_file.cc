#include "bodyrec/io/image_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <zlib.h>

#include "bodyrec/core/error.h"
#include "bodyrec/io/image_header.h"

namespace bodyrec {
namespace {

bool starts_with(const std::string& bytes, const char* prefix, size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), prefix, n) == 0;
}

uint32_t big_endian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// A PNG is a signature and chunks (4-byte big-endian length, type, data, CRC of type and data); it ends
// with IEND. Every chunk's CRC is checked here: on a mismatch libpng would print a line of its own before
// failing.
std::string png_reason(const std::string& bytes) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  size_t at = 8;
  while (at + 8 <= bytes.size()) {
    const unsigned char* p = data + at;
    const uint64_t length = big_endian32(p);
    const std::string type(reinterpret_cast<const char*>(p + 4), 4);
    if (length > 0x7fffffffu)  // the PNG specification's limit
      return "corrupt PNG file (chunk " + type + " at byte " + std::to_string(at) + " has an impossible length)";
    if (at + 12 + length > bytes.size()) break;
    if (crc32_z(crc32_z(0L, Z_NULL, 0), p + 4, static_cast<size_t>(4 + length)) != big_endian32(p + 8 + length))
      return "corrupt PNG file (chunk " + type + " at byte " + std::to_string(at) + " fails its CRC check)";
    if (type == "IEND") return "";
    at += 12 + length;
  }
  return "truncated PNG file (" + std::to_string(bytes.size()) + " bytes, no IEND chunk)";
}

// Markers cannot occur inside JPEG entropy-coded data (0xFF is stuffed as FF 00), so an end-of-image
// marker after the first start-of-scan means the file reached its end (an EXIF thumbnail's own markers
// come before the scan).
std::string jpeg_reason(const std::string& bytes) {
  const size_t scan = bytes.find("\xFF\xDA", 2);
  if (scan != std::string::npos && bytes.find("\xFF\xD9", scan + 2) != std::string::npos) return "";
  return "truncated JPEG file (" + std::to_string(bytes.size()) + " bytes, " +
         (scan == std::string::npos ? "no image scan" : "no end-of-image marker") + ")";
}

}  // namespace

std::string broken_image_reason(const std::string& bytes) {
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n", 8)) return png_reason(bytes);
  if (starts_with(bytes, "\xFF\xD8\xFF", 3)) return jpeg_reason(bytes);
  return "";
}

cv::Mat read_image_file(const std::string& path, int flags) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": missing");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": a directory, not an image");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
  // From the header, before the file (a 100 MP BMP is 300 MB) is read or decoded.
  if (const auto size = image_header_size(in)) check_frame_pixels(path, size->width, size->height);
  in.clear();
  in.seekg(0);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
  if (bytes.empty()) throw InputError(path + ": empty file");
  const std::string broken = broken_image_reason(bytes);
  if (!broken.empty()) throw InputError(path + ": " + broken);
  cv::Mat image;
  try {
    image = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())), flags);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) throw InputError(path + ": cannot decode image");
  check_frame_pixels(path, image.cols, image.rows);  // a format whose header is not read above
  return image;
}

}  // namespace bodyrec
