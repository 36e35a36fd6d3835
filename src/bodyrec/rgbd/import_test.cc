// NTU skeleton and PCD parsers on hand-made files, valid and broken.
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <liblzf/lzf.h>

#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/pcd.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;
using bodyrec::testing::write_text;

// A one-frame NTU file with `bodies` bodies; joint j of body b at (0.01 j + b, 0.02 j, 3).
std::string ntu_text(int bodies, const char* eol) {
  std::string s = std::string("1") + eol + std::to_string(bodies) + eol;
  for (int b = 0; b < bodies; ++b) {
    s += std::to_string(72057594037930000ULL + static_cast<unsigned>(b)) + " 0 1 1 1 1 0 0.1 -0.2 2" + eol + "25" + eol;
    for (int j = 0; j < 25; ++j) {
      const double x = 0.01 * j + b, y = 0.02 * j, z = 3.0;
      s += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + " 256 212 960 540 " +
           (j == 3 ? "0 0 0 0" : "1 0 0 0") + " 2" + eol;
    }
  }
  return s;
}

TEST(NtuSkeleton, ParsesLfAndCrlfAlike) {
  TempDir dir;
  write_text(dir / "lf.skeleton", ntu_text(2, "\n"));
  write_text(dir / "crlf.skeleton", ntu_text(2, "\r\n"));
  for (const char* name : {"lf.skeleton", "crlf.skeleton"}) {
    const NtuSkeleton s = read_ntu_skeleton((dir / name).string());
    ASSERT_EQ(s.frames.size(), 1u);
    ASSERT_EQ(s.frames[0].size(), 2u);
    EXPECT_EQ(s.frames[0][1].id, 72057594037930001ULL);
    EXPECT_NEAR(s.frames[0][1].joints[10].position[0], 1.1, 1e-9);
    EXPECT_EQ(s.frames[0][0].joints[3].orientation.norm(), 0.0);
  }
}

TEST(NtuSkeleton, ImportWritesBodiesOnlyWithNoOrientationForZeroQuaternions) {
  TempDir dir;
  write_text(dir / "a.skeleton", ntu_text(2, "\r\n"));
  double rms[2];
  EXPECT_EQ(import_ntu((dir / "a.skeleton").string(), (dir / "rec").string(), rms), 1);
  RecordingReader r((dir / "rec").string());
  EXPECT_TRUE(r.meta().streams.bodies);
  EXPECT_FALSE(r.meta().streams.color || r.meta().streams.depth);
  const RgbdFrame f = r.read_frame(0);
  EXPECT_TRUE(f.color.empty() && f.depth.empty());
  ASSERT_EQ(f.bodies.size(), 2u);
  EXPECT_EQ(f.bodies[1].index, 1);
  EXPECT_FALSE(f.bodies[0].joints[3].orientation);
  EXPECT_TRUE(f.bodies[0].joints[2].orientation);
  EXPECT_EQ(rms[0], -1);  // 50 joints of made-up projections cannot be fitted: Kinect defaults
}

TEST(NtuSkeleton, BrokenFilesNameTheLine) {
  TempDir dir;
  const auto error_of = [&](const std::string& text) {
    write_text(dir / "b.skeleton", text);
    return input_error([&] { read_ntu_skeleton((dir / "b.skeleton").string()); });
  };
  const std::string good = ntu_text(1, "\n");
  size_t cut = 0;
  for (int i = 0; i < 10; ++i) cut = good.find('\n', cut) + 1;
  EXPECT_TRUE(contains(error_of(good.substr(0, cut)), "unexpected end of file after line 10, expected joint line"));
  EXPECT_TRUE(contains(error_of("x\n"), "line 1: frame count: not an integer: \"x\""));
  EXPECT_TRUE(contains(error_of("1\n7\n"), "line 2: body count: 7 outside 0..6"));
  std::string bad = good;
  bad.replace(bad.find("\n25\n"), 4, "\n24\n");
  EXPECT_TRUE(contains(error_of(bad), "line 4: joint count: 24 outside 25..25"));
  bad = good;
  bad.replace(bad.find(" 2\n", bad.find("960 540")), 3, "\n");
  EXPECT_TRUE(contains(error_of(bad), "line 5: joint line"));
  bad = good;
  bad.replace(bad.find("960"), 3, "abc");
  EXPECT_TRUE(contains(error_of(bad), "line 5: joint value: not a number: \"abc\""));
  EXPECT_TRUE(contains(error_of(good + "1\n"), "unexpected data after the last frame"));
  EXPECT_TRUE(contains(input_error([&] { read_ntu_skeleton((dir / "none.skeleton").string()); }), "cannot open"));
}

// A 4x3 organised cloud with fx = fy = 10, cx = 1.5, cy = 1: point (u, v) at z = 2 + 0.1 u.
struct Cloud {
  std::vector<float> x, y, z;
  std::vector<uint32_t> rgba;
};
Cloud small_cloud() {
  Cloud c;
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 4; ++u) {
      const float z = 2.0f + 0.1f * static_cast<float>(u);
      c.x.push_back((static_cast<float>(u) - 1.5f) * z / 10.f);
      c.y.push_back((static_cast<float>(v) - 1.0f) * z / 10.f);
      c.z.push_back(z);
      c.rgba.push_back(0xff000000u | (10u * static_cast<unsigned>(u)) << 16 | 20u << 8 | (30u + static_cast<unsigned>(v)));
    }
  c.z[5] = std::nanf("");  // (u 1, v 1) has no point
  return c;
}
std::string header(const std::string& data, int width = 4, int height = 3) {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z rgba\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH " +
         std::to_string(width) + "\nHEIGHT " + std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(width * height) + "\nDATA " + data + "\n";
}
std::string bytes(const void* p, size_t n) { return std::string(static_cast<const char*>(p), n); }

void expect_small_cloud(const PcdCloud& c) {
  ASSERT_EQ(c.width, 4);
  ASSERT_EQ(c.height, 3);
  EXPECT_NEAR(c.xyz.at<cv::Vec3f>(2, 3)[2], 2.3f, 1e-6);
  EXPECT_TRUE(std::isnan(c.xyz.at<cv::Vec3f>(1, 1)[2]));
  EXPECT_EQ(c.color.at<cv::Vec3b>(2, 3), cv::Vec3b(32, 20, 30));  // BGR
}

TEST(Pcd, ReadsAsciiBinaryAndBinaryCompressed) {
  TempDir dir;
  const Cloud c = small_cloud();
  std::string ascii = header("ascii");
  for (size_t i = 0; i < c.z.size(); ++i)
    ascii += std::to_string(c.x[i]) + " " + std::to_string(c.y[i]) + " " + (std::isnan(c.z[i]) ? "nan" : std::to_string(c.z[i])) +
             " " + std::to_string(c.rgba[i]) + "\n";
  write_text(dir / "a.pcd", ascii);
  std::string binary = header("binary");
  for (size_t i = 0; i < c.z.size(); ++i)
    binary += bytes(&c.x[i], 4) + bytes(&c.y[i], 4) + bytes(&c.z[i], 4) + bytes(&c.rgba[i], 4);
  write_text(dir / "b.pcd", binary);
  // binary_compressed: field-major, then LZF (Debian liblzf compresses; the reader decompresses).
  const std::string raw = bytes(c.x.data(), 48) + bytes(c.y.data(), 48) + bytes(c.z.data(), 48) + bytes(c.rgba.data(), 48);
  std::vector<char> packed(raw.size() * 2 + 16);
  const unsigned n = lzf_compress(raw.data(), static_cast<unsigned>(raw.size()), packed.data(), static_cast<unsigned>(packed.size()));
  ASSERT_GT(n, 0u);
  const uint32_t sizes[2] = {n, static_cast<uint32_t>(raw.size())};
  write_text(dir / "c.pcd", header("binary_compressed") + bytes(sizes, 8) + std::string(packed.data(), n));
  for (const char* name : {"a.pcd", "b.pcd", "c.pcd"}) {
    SCOPED_TRACE(name);
    const PcdCloud cloud = read_pcd((dir / name).string());
    expect_small_cloud(cloud);
    EXPECT_TRUE(contains(input_error([&] { fit_pcd_intrinsics(cloud, name); }), "fewer than 100 valid points"));
  }
  // Broken compressed payloads.
  const auto error_of = [&](const std::string& text) {
    write_text(dir / "x.pcd", text);
    return input_error([&] { read_pcd((dir / "x.pcd").string()); });
  };
  EXPECT_TRUE(contains(error_of(header("binary_compressed") + bytes(sizes, 8) + std::string(packed.data(), n / 2)),
                       "binary_compressed: data truncated"));
  const uint32_t wrong[2] = {n, 100};
  EXPECT_TRUE(contains(error_of(header("binary_compressed") + bytes(wrong, 8) + std::string(packed.data(), n)),
                       "uncompressed size 100 disagrees with the header (192 bytes)"));
  std::string corrupt(packed.data(), n);
  corrupt[0] = static_cast<char>(0xff);  // a back reference before the start
  EXPECT_TRUE(contains(error_of(header("binary_compressed") + bytes(sizes, 8) + corrupt), "LZF data corrupt"));
  EXPECT_TRUE(contains(error_of(header("binary") + binary.substr(header("binary").size(), 100)), "binary data truncated: 100 of 192 bytes"));
  EXPECT_TRUE(contains(error_of(header("ascii") + "1 2 3\n"), "ascii point 0: 3 values, expected 4"));
  EXPECT_TRUE(contains(error_of(header("ascii") + "1 2 z 4\n"), "ascii point 0: field z: not a number"));
  EXPECT_TRUE(contains(error_of(header("lzma")), "expected ascii, binary or binary_compressed"));
  EXPECT_TRUE(contains(error_of(header("binary", 12, 1)), "HEIGHT 1: the cloud is not organised"));
  std::string h = header("binary");
  h.replace(h.find("POINTS 12"), 9, "POINTS 11");
  EXPECT_TRUE(contains(error_of(h), "POINTS 11 is not WIDTH x HEIGHT"));
  h = header("binary");
  h.replace(h.find("rgba"), 4, "intensity");
  EXPECT_TRUE(contains(error_of(h), "no field rgb or rgba"));
  h = header("binary");
  h.replace(h.find("SIZE 4 4 4 4"), 12, "SIZE 4 4 4");
  EXPECT_TRUE(contains(error_of(h), "SIZE and TYPE need one value per field"));
  EXPECT_TRUE(contains(error_of("hello\n"), "unknown header key"));
  EXPECT_TRUE(contains(error_of("VERSION 0.7\n"), "no DATA line"));
}

TEST(Pcd, AsciiRgbAsPclWritesIt) {
  // PCL writes the packed colour of an `rgb` F field as the float with the same bits, e.g. 4.2108e+06.
  TempDir dir;
  const uint32_t packed = 200u << 16 | 100u << 8 | 50u;
  float as_float;
  std::memcpy(&as_float, &packed, 4);
  char value[64];
  std::snprintf(value, sizeof value, "%.9g", static_cast<double>(as_float));
  std::string text = "VERSION .7\r\nFIELDS x y z rgb\r\nSIZE 4 4 4 4\r\nTYPE F F F F\r\nWIDTH 2\r\nHEIGHT 2\r\n"
                     "POINTS 4\r\nDATA ascii\r\n";
  for (int i = 0; i < 4; ++i) text += "0.1 0.2 1.5 " + std::string(value) + "\r\n";
  write_text(dir / "rgb.pcd", text);
  const PcdCloud c = read_pcd((dir / "rgb.pcd").string());
  EXPECT_EQ(c.color.at<cv::Vec3b>(1, 1), cv::Vec3b(50, 100, 200));
  EXPECT_FLOAT_EQ(c.xyz.at<cv::Vec3f>(1, 1)[2], 1.5f);
}

TEST(Pcd, ImportWritesRegisteredColourAndDepthInMillimetres) {
  TempDir dir;
  // 20x15 cloud from a pinhole (fx = fy = 20, cx = 9.5, cy = 7), one NaN.
  std::string binary = header("binary", 20, 15);
  for (int v = 0; v < 15; ++v)
    for (int u = 0; u < 20; ++u) {
      const float z = 1.5f + 0.01f * static_cast<float>(u + v);
      const float x = (static_cast<float>(u) - 9.5f) * z / 20.f, y = (static_cast<float>(v) - 7.f) * z / 20.f;
      const float zz = (u == 4 && v == 2) ? std::nanf("") : z;
      const uint32_t rgba = 0xff000000u | 200u << 16 | 100u << 8 | 50u;
      binary += bytes(&x, 4) + bytes(&y, 4) + bytes(&zz, 4) + bytes(&rgba, 4);
    }
  write_text(dir / "c.pcd", binary);
  double rms = 0;
  const Intrinsics k = import_pcd((dir / "c.pcd").string(), (dir / "rec").string(), &rms);
  EXPECT_NEAR(k.fx, 20, 1e-3);
  EXPECT_NEAR(k.cy, 7, 1e-3);
  EXPECT_LT(rms, 1e-3);
  const RgbdFrame f = RecordingReader((dir / "rec").string()).read_frame(0);
  EXPECT_EQ(f.depth.at<uint16_t>(2, 4), 0);
  EXPECT_EQ(f.depth.at<uint16_t>(3, 10), 1630);
  EXPECT_EQ(f.color.at<cv::Vec3b>(0, 0), cv::Vec3b(50, 100, 200));
}

// Fuzz finding (fuzz/regressions/pcd): an integer colour beyond 32 bits was cast to long long (undefined
// behaviour, caught by UBSan); now a typed error naming the point and field.
TEST(Pcd, FuzzAsciiPackedColourOutOfRangeIsAnInputError) {
  std::istringstream in(
      "FIELDS x y z rgba\nSIZE 4 4 4 4\nTYPE F F F U\nWIDTH 1\nHEIGHT 2\nPOINTS 2\nDATA ascii\n0 0 1 1e25\n0 0 1 0\n");
  EXPECT_EQ(input_error([&] { read_pcd(in, "c.pcd"); }),
            "c.pcd: ascii point 0: field rgba: not a packed 32-bit colour: \"1e25\"");
  std::istringstream signed_colour(
      "FIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F I\nWIDTH 1\nHEIGHT 2\nPOINTS 2\nDATA ascii\n0 0 1 -1\n0 0 1 255\n");
  const PcdCloud c = read_pcd(signed_colour, "s.pcd");
  EXPECT_EQ(c.color.at<cv::Vec3b>(0, 0), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(c.color.at<cv::Vec3b>(1, 0), cv::Vec3b(255, 0, 0));
}

// Fuzz finding (fuzz/regressions/pcd: huge_*, too_many_points): a header promising billions of points or a
// COUNT of 2^31 made read_pcd allocate gigabytes (out of memory) before it looked at the data. Now the
// header is bounded and the data length is checked against it before any allocation.
TEST(Pcd, FuzzHeadersPromisingMoreThanTheDataAreRefusedBeforeAllocating) {
  const auto error_of = [](const std::string& header, const std::string& data) {
    std::istringstream in("FIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F F\n" + header + data, std::ios::binary);
    return input_error([&] { read_pcd(in, "h.pcd"); });
  };
  const std::string big = "WIDTH 8000\nHEIGHT 8000\nPOINTS 64000000\n";
  EXPECT_EQ(error_of("COUNT 1 1 1 2147483647\nWIDTH 2\nHEIGHT 2\nPOINTS 4\nDATA binary\n", "0000"),
            "h.pcd: header: field rgb: bad SIZE or COUNT");
  EXPECT_EQ(error_of("WIDTH 50000\nHEIGHT 40000\nPOINTS 2000000000\nDATA binary\n", "0000"),
            "h.pcd: header: 2000000000 points, more than bodyrec reads (67108864)");
  EXPECT_EQ(error_of(big + "DATA binary\n", "0000"), "h.pcd: binary data truncated: 4 of 1024000000 bytes");
  EXPECT_EQ(error_of(big + "DATA binary_compressed\n", std::string("\x10\0\0\0\0\xa0\x41\x0f", 8) + "0123456789abcdef"),
            "h.pcd: binary_compressed: data truncated: 24 bytes cannot hold 64000000 points");
  EXPECT_EQ(error_of(big + "DATA ascii\n", "1 2 3 4\n"), "h.pcd: ascii data truncated: 8 bytes cannot hold 64000000 points");
}

}  // namespace
}  // namespace bodyrec
