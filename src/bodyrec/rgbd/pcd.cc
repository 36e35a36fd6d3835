#include "bodyrec/rgbd/pcd.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include <liblzf/lzf.h>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {
namespace {

struct Field {
  std::string name;
  int size = 4;
  char type = 'F';
  int count = 1;
  size_t offset = 0;  // byte offset within a point record (binary)
};

struct Header {
  std::vector<Field> fields;
  int width = 0, height = 0;
  long long points = 0;
  std::string data;
  size_t point_bytes = 0;
};

[[noreturn]] void fail(const std::string& file, const std::string& what) { throw InputError(file + ": " + what); }

// Sanity bounds, far above any sensor (a Kinect v2 colour frame is 2 megapixels; PCL descriptors have
// COUNT up to a few hundred): a corrupt header must not make us allocate gigabytes before reading data.
constexpr long long kMaxPoints = 8192LL * 8192;
constexpr int kMaxCount = 65536;
constexpr size_t kMaxFields = 1024;

// Bytes between the read position and the end of a seekable stream; nullopt when it cannot be told.
std::optional<size_t> bytes_left(std::istream& in) {
  const std::streampos here = in.tellg();
  if (here < 0) return std::nullopt;
  in.seekg(0, std::ios::end);
  const std::streampos end = in.tellg();
  in.clear();
  in.seekg(here);
  if (end < here) return std::nullopt;
  return static_cast<size_t>(end - here);
}

int to_int(const std::string& file, int line, const std::string& t) {
  const long long v = parse_integer(t).value_or(-1);
  if (v < 0 || v > std::numeric_limits<int>::max())
    fail(file, "header line " + std::to_string(line) + ": not a non-negative integer: \"" + t + "\"");
  return static_cast<int>(v);
}

Header read_header(std::istream& in, const std::string& file) {
  Header h;
  std::vector<std::string> sizes, types, counts;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key;
    s >> key;
    std::vector<std::string> v;
    for (std::string t; s >> t;) v.push_back(t);
    const std::string at = "header line " + std::to_string(line_no) + " (" + key + ")";
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS" || key == "COLUMNS") {
      for (const auto& n : v) h.fields.push_back({n});
    } else if (key == "SIZE") {
      sizes = v;
    } else if (key == "TYPE") {
      types = v;
    } else if (key == "COUNT") {
      counts = v;
    } else if (key == "WIDTH") {
      if (v.size() != 1) fail(file, at + ": expected one value");
      h.width = to_int(file, line_no, v[0]);
    } else if (key == "HEIGHT") {
      if (v.size() != 1) fail(file, at + ": expected one value");
      h.height = to_int(file, line_no, v[0]);
    } else if (key == "POINTS") {
      if (v.size() != 1) fail(file, at + ": expected one value");
      h.points = to_int(file, line_no, v[0]);
    } else if (key == "DATA") {
      if (v.size() != 1 || (v[0] != "ascii" && v[0] != "binary" && v[0] != "binary_compressed"))
        fail(file, at + ": expected ascii, binary or binary_compressed");
      h.data = v[0];
      break;
    } else {
      fail(file, at + ": unknown header key (not a PCD file?)");
    }
  }
  if (h.data.empty()) fail(file, "no DATA line (not a PCD file, or truncated header)");
  if (h.fields.empty()) fail(file, "header: FIELDS missing");
  if (h.fields.size() > kMaxFields) fail(file, "header: more than " + std::to_string(kMaxFields) + " FIELDS");
  if (sizes.size() != h.fields.size() || types.size() != h.fields.size())
    fail(file, "header: SIZE and TYPE need one value per field (" + std::to_string(h.fields.size()) + ")");
  if (!counts.empty() && counts.size() != h.fields.size()) fail(file, "header: COUNT needs one value per field");
  for (size_t i = 0; i < h.fields.size(); ++i) {
    Field& f = h.fields[i];
    f.size = to_int(file, 0, sizes[i]);
    if (types[i].size() != 1 || std::string("FUI").find(types[i][0]) == std::string::npos)
      fail(file, "header: TYPE of field " + f.name + " must be F, U or I");
    f.type = types[i][0];
    f.count = counts.empty() ? 1 : to_int(file, 0, counts[i]);
    if (!(f.size == 1 || f.size == 2 || f.size == 4 || f.size == 8) || f.count < 1 || f.count > kMaxCount)
      fail(file, "header: field " + f.name + ": bad SIZE or COUNT");
    f.offset = h.point_bytes;
    h.point_bytes += static_cast<size_t>(f.size) * static_cast<size_t>(f.count);
  }
  if (h.width <= 0 || h.height <= 0) fail(file, "header: WIDTH and HEIGHT must be positive");
  if (h.points != static_cast<long long>(h.width) * h.height)
    fail(file, "header: POINTS " + std::to_string(h.points) + " is not WIDTH x HEIGHT");
  if (h.height == 1) fail(file, "header: HEIGHT 1: the cloud is not organised (no pixel grid to make images of)");
  if (h.points > kMaxPoints)
    fail(file, "header: " + std::to_string(h.points) + " points, more than bodyrec reads (" + std::to_string(kMaxPoints) + ")");
  return h;
}

const Field& field(const Header& h, const std::string& file, const std::vector<std::string>& names) {
  for (const auto& f : h.fields)
    for (const auto& n : names)
      if (f.name == n) return f;
  fail(file, "header: no field " + names.front() + (names.size() > 1 ? " or " + names[1] : ""));
}

// A value of a field as double (floats), or its raw 32 bits (colour).
double as_double(const Field& f, const unsigned char* p) {
  if (f.type == 'F' && f.size == 4) {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  if (f.type == 'F' && f.size == 8) {
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

uint32_t as_bits(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

PcdCloud read_pcd(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot open");
  return read_pcd(in, file);
}

PcdCloud read_pcd(std::istream& in, const std::string& file) {
  const Header h = read_header(in, file);
  const Field& fx = field(h, file, {"x"});
  const Field& fy = field(h, file, {"y"});
  const Field& fz = field(h, file, {"z"});
  const Field& fc = field(h, file, {"rgb", "rgba"});
  for (const Field* f : {&fx, &fy, &fz})
    if (f->type != 'F') fail(file, "header: field " + f->name + " must be TYPE F");
  if (fc.size != 4) fail(file, "header: field " + fc.name + " must be SIZE 4");
  const size_t n = static_cast<size_t>(h.points);
  // Refuse data shorter than the header promises before allocating for it: points * bytes per point for
  // binary; the size words and the smallest LZF block that could hold the points for binary_compressed
  // (LZF expands at most 88-fold); for ascii, one character per value, checked only for large clouds so
  // that a short small file still gets the message naming its first bad point.
  size_t values = 0;
  for (const auto& f : h.fields) values += static_cast<size_t>(f.count);
  if (const auto left = bytes_left(in)) {
    if (h.data == "binary" && *left < n * h.point_bytes)
      fail(file, "binary data truncated: " + std::to_string(*left) + " of " + std::to_string(n * h.point_bytes) + " bytes");
    if (h.data == "binary_compressed" && *left < 8 + n * h.point_bytes / 100)
      fail(file, "binary_compressed: data truncated: " + std::to_string(*left) + " bytes cannot hold " +
                     std::to_string(n) + " points");
    if (h.data == "ascii" && n >= (1u << 16) && *left < n * values)
      fail(file, "ascii data truncated: " + std::to_string(*left) + " bytes cannot hold " + std::to_string(n) + " points");
  }
  PcdCloud c;
  c.width = h.width;
  c.height = h.height;
  c.xyz.create(h.height, h.width, CV_32FC3);
  c.color.create(h.height, h.width, CV_8UC3);
  auto* xyz = c.xyz.ptr<cv::Vec3f>();
  auto* bgr = c.color.ptr<cv::Vec3b>();
  const auto set_color = [&](size_t i, uint32_t v) {
    bgr[i] = {static_cast<uint8_t>(v & 0xff), static_cast<uint8_t>((v >> 8) & 0xff), static_cast<uint8_t>((v >> 16) & 0xff)};
  };

  if (h.data == "ascii") {
    // One point per line; colour is the packed integer written as a float (PCL) or as an integer.
    std::string line;
    size_t i = 0;
    for (; i < n && std::getline(in, line); ++i) {
      std::istringstream s(line);
      std::vector<std::string> v;
      for (std::string t; s >> t;) v.push_back(t);
      if (v.size() != values)
        fail(file, "ascii point " + std::to_string(i) + ": " + std::to_string(v.size()) + " values, expected " +
                       std::to_string(values));
      size_t col = 0;
      for (const auto& f : h.fields) {
        const std::string& t = v[col];
        col += static_cast<size_t>(f.count);
        const bool is_nan = t == "nan" || t == "NaN" || t == "-nan";
        double d = std::numeric_limits<double>::quiet_NaN();
        if (!is_nan) {
          const auto parsed = parse_double(t);
          if (parsed) d = *parsed;
          else fail(file, "ascii point " + std::to_string(i) + ": field " + f.name + ": not a number: \"" + t + "\"");
        }
        if (&f == &fx) xyz[i][0] = static_cast<float>(d);
        if (&f == &fy) xyz[i][1] = static_cast<float>(d);
        if (&f == &fz) xyz[i][2] = static_cast<float>(d);
        if (&f == &fc) {
          uint32_t bits = 0;
          if (fc.type == 'F') {
            const float fv = static_cast<float>(d);
            std::memcpy(&bits, &fv, 4);
          } else if (!is_nan) {
            // A packed colour: 32 bits, written unsigned (U) or signed (I). Out of range would overflow.
            if (!(d >= -2147483648.0 && d <= 4294967295.0))
              fail(file, "ascii point " + std::to_string(i) + ": field " + f.name + ": not a packed 32-bit colour: \"" +
                             t + "\"");
            bits = static_cast<uint32_t>(static_cast<long long>(d));
          }
          set_color(i, bits);
        }
      }
    }
    if (i != n) fail(file, "ascii data ends after " + std::to_string(i) + " of " + std::to_string(n) + " points");
    return c;
  }

  std::vector<unsigned char> data;
  const size_t expected = n * h.point_bytes;
  if (h.data == "binary") {
    data.resize(expected);
    in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(expected));
    if (static_cast<size_t>(in.gcount()) != expected)
      fail(file, "binary data truncated: " + std::to_string(in.gcount()) + " of " + std::to_string(expected) + " bytes");
    for (size_t i = 0; i < n; ++i) {
      const unsigned char* p = data.data() + i * h.point_bytes;
      xyz[i] = {static_cast<float>(as_double(fx, p + fx.offset)), static_cast<float>(as_double(fy, p + fy.offset)),
                static_cast<float>(as_double(fz, p + fz.offset))};
      set_color(i, as_bits(p + fc.offset));
    }
    return c;
  }

  // binary_compressed: uint32 compressed size, uint32 uncompressed size, LZF block; field-major after.
  uint32_t sizes[2] = {0, 0};
  in.read(reinterpret_cast<char*>(sizes), 8);
  if (in.gcount() != 8) fail(file, "binary_compressed: missing the two size words");
  if (sizes[1] != expected)
    fail(file, "binary_compressed: uncompressed size " + std::to_string(sizes[1]) + " disagrees with the header (" +
                   std::to_string(expected) + " bytes)");
  if (const auto left = bytes_left(in); left && *left < sizes[0])
    fail(file, "binary_compressed: data truncated: " + std::to_string(*left) + " of " + std::to_string(sizes[0]) +
                   " compressed bytes");
  std::vector<unsigned char> packed(sizes[0]);
  in.read(reinterpret_cast<char*>(packed.data()), static_cast<std::streamsize>(sizes[0]));
  if (static_cast<size_t>(in.gcount()) != sizes[0])
    fail(file, "binary_compressed: data truncated: " + std::to_string(in.gcount()) + " of " + std::to_string(sizes[0]) +
                   " compressed bytes");
  data.resize(expected);
  const unsigned got = lzf_decompress(packed.data(), sizes[0], data.data(), static_cast<unsigned>(expected));
  if (got != expected) fail(file, "binary_compressed: LZF data corrupt (decompressed " + std::to_string(got) + " bytes)");
  // Field-major: each field's values for all points are contiguous, fields in header order.
  const auto column = [&](const Field& f) { return data.data() + f.offset * n; };
  const unsigned char *cx = column(fx), *cy = column(fy), *cz = column(fz), *cc = column(fc);
  const size_t sx = static_cast<size_t>(fx.size * fx.count), sy = static_cast<size_t>(fy.size * fy.count),
               sz = static_cast<size_t>(fz.size * fz.count), sc = static_cast<size_t>(fc.size * fc.count);
  for (size_t i = 0; i < n; ++i) {
    xyz[i] = {static_cast<float>(as_double(fx, cx + i * sx)), static_cast<float>(as_double(fy, cy + i * sy)),
              static_cast<float>(as_double(fz, cz + i * sz))};
    set_color(i, as_bits(cc + i * sc));
  }
  return c;
}

Intrinsics fit_pcd_intrinsics(const PcdCloud& c, const std::string& file, double* rms_px) {
  // Normal equations of two independent lines: u = fx (x/z) + cx, v = fy (y/z) + cy.
  double su[5] = {0, 0, 0, 0, 0}, sv[5] = {0, 0, 0, 0, 0};  // n, sum a, sum a^2, sum p, sum a p
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const cv::Vec3f p = c.xyz.at<cv::Vec3f>(v, u);
      if (!(p[2] > 0) || !std::isfinite(p[0]) || !std::isfinite(p[1])) continue;
      const double a = p[0] / p[2], b = p[1] / p[2];
      su[0] += 1, su[1] += a, su[2] += a * a, su[3] += u, su[4] += a * u;
      sv[0] += 1, sv[1] += b, sv[2] += b * b, sv[3] += v, sv[4] += b * v;
    }
  if (su[0] < 100) fail(file, "fewer than 100 valid points: cannot fit camera intrinsics");
  const auto solve = [](const double* s, double& slope, double& offset) {
    const double det = s[0] * s[2] - s[1] * s[1];
    slope = (s[0] * s[4] - s[1] * s[3]) / det;
    offset = (s[3] - slope * s[1]) / s[0];
  };
  Intrinsics k;
  k.width = c.width;
  k.height = c.height;
  solve(su, k.fx, k.cx);
  solve(sv, k.fy, k.cy);
  if (!(k.fx > 0) || !(k.fy > 0)) fail(file, "points do not follow a pinhole camera (fitted focal length not positive)");
  if (rms_px) {
    double e = 0;
    for (int v = 0; v < c.height; ++v)
      for (int u = 0; u < c.width; ++u) {
        const cv::Vec3f p = c.xyz.at<cv::Vec3f>(v, u);
        if (!(p[2] > 0) || !std::isfinite(p[0]) || !std::isfinite(p[1])) continue;
        const double du = k.cx + k.fx * p[0] / p[2] - u, dv = k.cy + k.fy * p[1] / p[2] - v;
        e += du * du + dv * dv;
      }
    *rms_px = std::sqrt(e / su[0]);
  }
  return k;
}

Intrinsics import_pcd(const std::string& file, const std::string& out_dir, double* rms_px) {
  const PcdCloud c = read_pcd(file);
  const Intrinsics k = fit_pcd_intrinsics(c, file, rms_px);
  RecordingMeta meta;
  meta.sensor = "PCD organised cloud (" + file.substr(file.find_last_of('/') + 1) + ")";
  meta.depth = meta.color = k;  // colour registered to depth: one camera
  meta.streams.color = meta.streams.depth = true;
  RgbdFrame frame;
  frame.color = c.color;
  frame.depth = cv::Mat::zeros(c.height, c.width, CV_16U);
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const float z = c.xyz.at<cv::Vec3f>(v, u)[2];
      if (z > 0 && z < 65.535f) frame.depth.at<uint16_t>(v, u) = static_cast<uint16_t>(std::lround(z * 1000.0f));
    }
  RecordingWriter writer(out_dir, meta);
  writer.write(frame);
  return k;
}

}  // namespace bodyrec
