#include "bodyrec/io/image_header.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

using Bytes = std::vector<unsigned char>;

// Reads exactly n bytes, or returns false.
bool read_bytes(std::istream& in, Bytes& out, size_t n) {
  out.resize(n);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
  return in.gcount() == static_cast<std::streamsize>(n);
}

uint32_t be16(const unsigned char* p) { return (uint32_t{p[0]} << 8) | p[1]; }
uint32_t be32(const unsigned char* p) { return (be16(p) << 16) | be16(p + 2); }
uint32_t le16(const unsigned char* p) { return (uint32_t{p[1]} << 8) | p[0]; }
uint32_t le24(const unsigned char* p) { return (uint32_t{p[2]} << 16) | le16(p); }
uint32_t le32(const unsigned char* p) { return (uint32_t{p[3]} << 24) | le24(p); }

std::optional<cv::Size> size_of(int64_t width, int64_t height) {
  if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX) return std::nullopt;
  return cv::Size(static_cast<int>(width), static_cast<int>(height));
}

// After the signature (8 bytes, already read): IHDR's length (4), "IHDR", width, height (big-endian).
std::optional<cv::Size> png_size(std::istream& in) {
  Bytes b;
  if (!read_bytes(in, b, 8) || std::memcmp(b.data() + 4, "IHDR", 4) != 0 || !read_bytes(in, b, 8)) return std::nullopt;
  return size_of(be32(b.data()), be32(b.data() + 4));
}

// Segments after SOI (the first 2 bytes, already read): FF marker, then a 2-byte length that counts itself,
// except for the markers that stand alone. The size is in the first start-of-frame (C0-CF but C4 DHT,
// C8 JPG, CC DAC): precision (1), height (2), width (2).
std::optional<cv::Size> jpeg_size(std::istream& in) {
  Bytes b;
  for (int segments = 0; segments < 1000; ++segments) {
    int c = in.get();
    if (c != 0xFF) return std::nullopt;
    while (c == 0xFF) c = in.get();  // fill bytes
    if (c == EOF) return std::nullopt;
    if (c == 0x01 || (c >= 0xD0 && c <= 0xD8)) continue;  // TEM, RSTn, SOI: no length
    if (c == 0xD9 || c == 0xDA) return std::nullopt;     // end of image or a scan before any frame header
    if (!read_bytes(in, b, 2) || be16(b.data()) < 2) return std::nullopt;
    const uint32_t length = be16(b.data());
    if (c >= 0xC0 && c <= 0xCF && c != 0xC4 && c != 0xC8 && c != 0xCC) {
      if (length < 7 || !read_bytes(in, b, 5)) return std::nullopt;
      return size_of(be16(b.data() + 3), be16(b.data() + 1));  // height 0 (set by a later DNL): nullopt
    }
    in.seekg(length - 2, std::ios::cur);
    if (!in) return std::nullopt;
  }
  return std::nullopt;
}

// "BM", file header (14 bytes), then the info header: its size (4), then width and height as int32
// (int16 in the 12-byte OS/2 core header); a negative height means rows run top-down. `head` holds the
// file's first 30 bytes or fewer.
std::optional<cv::Size> bmp_size(const Bytes& head) {
  if (head.size() < 26) return std::nullopt;
  if (le32(head.data() + 14) == 12) return size_of(le16(head.data() + 18), le16(head.data() + 20));
  const int64_t height = static_cast<int32_t>(le32(head.data() + 22));
  return size_of(static_cast<int32_t>(le32(head.data() + 18)), height < 0 ? -height : height);
}

// "RIFF", size, "WEBP", then the first chunk: "VP8 " (lossy: a 3-byte frame tag, the start code 9D 01 2A,
// then 14-bit width and height), "VP8L" (lossless: signature 2F, then width-1 and height-1 in 14 bits
// each) or "VP8X" (extended: flags, 3 reserved bytes, canvas width-1 and height-1 in 24 bits each).
std::optional<cv::Size> webp_size(const Bytes& head) {
  if (head.size() < 30) return std::nullopt;
  const unsigned char* chunk = head.data() + 12;
  const unsigned char* data = head.data() + 20;
  if (std::memcmp(chunk, "VP8 ", 4) == 0) {
    if (data[3] != 0x9D || data[4] != 0x01 || data[5] != 0x2A) return std::nullopt;
    return size_of(le16(data + 6) & 0x3FFF, le16(data + 8) & 0x3FFF);
  }
  if (std::memcmp(chunk, "VP8L", 4) == 0) {
    if (data[0] != 0x2F) return std::nullopt;
    const uint32_t bits = le32(data + 1);
    return size_of((bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1);
  }
  if (std::memcmp(chunk, "VP8X", 4) == 0) return size_of(int64_t{le24(data + 4)} + 1, int64_t{le24(data + 7)} + 1);
  return std::nullopt;
}

// "II*\0" (little-endian) or "MM\0*" (big-endian), the first directory's offset; the directory is a count
// and 12-byte entries (tag, type, count, value): ImageWidth (256) and ImageLength (257), SHORT or LONG.
std::optional<cv::Size> tiff_size(std::istream& in, const Bytes& head) {
  const bool little = head[0] == 'I';
  const auto u16 = [little](const unsigned char* p) { return little ? le16(p) : be16(p); };
  const auto u32 = [little](const unsigned char* p) { return little ? le32(p) : be32(p); };
  if (u16(head.data() + 2) != 42) return std::nullopt;  // 43 is BigTIFF: left to the decoder
  in.clear();
  in.seekg(u32(head.data() + 4));
  Bytes b;
  if (!in || !read_bytes(in, b, 2)) return std::nullopt;
  const uint32_t entries = u16(b.data());
  int64_t width = 0, height = 0;
  for (uint32_t i = 0; i < entries && i < 4096; ++i) {
    if (!read_bytes(in, b, 12)) return std::nullopt;
    const uint32_t tag = u16(b.data()), type = u16(b.data() + 2);
    if (tag != 256 && tag != 257) continue;
    const int64_t value = type == 3 ? u16(b.data() + 8) : type == 4 ? u32(b.data() + 8) : 0;
    (tag == 256 ? width : height) = value;
  }
  return size_of(width, height);
}

// "P1".."P6", then width and height as decimal text, separated by white space and '#' comments.
std::optional<cv::Size> pnm_size(std::istream& in) {
  int64_t values[2] = {0, 0};
  int read = 0;
  for (int budget = 4096; budget > 0 && read < 2; --budget) {
    int c = in.get();
    if (c == '#') {
      while (c != EOF && c != '\n' && c != '\r' && --budget > 0) c = in.get();
      continue;
    }
    if (std::isspace(c)) continue;
    if (!std::isdigit(c)) return std::nullopt;
    int64_t v = 0;
    for (; std::isdigit(c) && v < INT32_MAX; c = in.get()) v = v * 10 + (c - '0');
    if (!std::isspace(c) && c != '#') return std::nullopt;
    if (c == '#') in.unget();
    values[read++] = v;
  }
  if (read < 2) return std::nullopt;
  return size_of(values[0], values[1]);
}

}  // namespace

std::string frame_pixels_problem(int64_t width, int64_t height) {
  const int64_t pixels = width * height;
  if (pixels <= kMaxFramePixels) return "";
  char mp[32];
  std::snprintf(mp, sizeof mp, "%.1f", static_cast<double>(pixels) / 1e6);
  return std::to_string(width) + "x" + std::to_string(height) + " pixels (" + mp + " MP) exceeds the " +
         std::to_string(kMaxFramePixels / 1'000'000) + " MP limit per frame";
}

void check_frame_pixels(const std::string& what, int64_t width, int64_t height) {
  const std::string problem = frame_pixels_problem(width, height);
  if (!problem.empty()) throw InputError(what + ": " + problem);
}

std::optional<cv::Size> image_header_size(std::istream& in) {
  Bytes head;
  read_bytes(in, head, 30);
  head.resize(static_cast<size_t>(std::max<std::streamsize>(0, in.gcount())));
  const auto starts = [&head](const char* magic, size_t n) {
    return head.size() >= n && std::memcmp(head.data(), magic, n) == 0;
  };
  const auto from = [&in](std::streamoff offset) -> std::istream& {
    in.clear();
    in.seekg(offset);
    return in;
  };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return png_size(from(8));
  if (starts("\xFF\xD8", 2)) return jpeg_size(from(2));
  if (starts("BM", 2)) return bmp_size(head);
  if (starts("RIFF", 4) && head.size() >= 12 && std::memcmp(head.data() + 8, "WEBP", 4) == 0) return webp_size(head);
  if (head.size() >= 8 && (starts("II", 2) || starts("MM", 2))) return tiff_size(in, head);
  if (head.size() >= 3 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6') return pnm_size(from(2));
  return std::nullopt;
}

std::optional<cv::Size> image_header_size(const std::string& bytes) {
  std::istringstream in(bytes);
  return image_header_size(in);
}

std::optional<cv::Size> image_file_header_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return image_header_size(in);
}

}  // namespace bodyrec
