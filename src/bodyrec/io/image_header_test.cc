#include "bodyrec/io/image_header.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "bodyrec/io/frame_source.h"
#include "bodyrec/io/image_file.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::input_error;

std::string encoded(const std::string& ext, cv::Size size, int type = CV_8UC3, std::vector<int> params = {}) {
  cv::Mat image(size, type);
  cv::RNG(5).fill(image, cv::RNG::UNIFORM, 0, 256);
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes, params)) << ext;
  return std::string(bytes.begin(), bytes.end());
}

std::string be32(uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

// A PNG whose header says width x height, with no image data (a decoder refuses it; the header check
// must refuse it first).
std::string png_header(uint32_t width, uint32_t height) {
  return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + "IHDR" + be32(width) + be32(height) +
         std::string("\x08\x02\x00\x00\x00", 5) + be32(0) + be32(0) + "IEND" + be32(0xAE426082);
}

TEST(ImageHeader, SizesOfEveryFormatOpenCvWrites) {
  const cv::Size size(123, 45);
  for (const char* ext : {".png", ".jpg", ".bmp", ".tif", ".ppm", ".pgm", ".webp"}) {
    SCOPED_TRACE(ext);
    if (!cv::haveImageWriter(ext)) continue;
    const int type = std::string(ext) == ".pgm" ? CV_8UC1 : CV_8UC3;
    const auto got = image_header_size(encoded(ext, size, type));
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(*got, size);
  }
  // Progressive JPEG (SOF2), 16-bit PNG, lossless WebP (VP8L), grey and 32-bit-alpha BMP.
  EXPECT_EQ(image_header_size(encoded(".jpg", size, CV_8UC3, {cv::IMWRITE_JPEG_PROGRESSIVE, 1})), size);
  EXPECT_EQ(image_header_size(encoded(".png", size, CV_16UC1)), size);
  if (cv::haveImageWriter(".webp")) {
    EXPECT_EQ(image_header_size(encoded(".webp", size, CV_8UC3, {cv::IMWRITE_WEBP_QUALITY, 101})), size);
  }
  EXPECT_EQ(image_header_size(encoded(".bmp", size, CV_8UC1)), size);
  EXPECT_EQ(image_header_size(encoded(".bmp", size, CV_8UC4)), size);
}

TEST(ImageHeader, JpegSizeAfterAnExifSegmentAndBigEndianTiff) {
  const cv::Size size(640, 7);
  const std::string jpg = encoded(".jpg", size);
  // APP1 "Exif" of 3000 bytes holding a thumbnail-like SOF0 marker that must be skipped, not read.
  std::string app1 = "Exif" + std::string(2, '\0') + std::string("\xFF\xC0\x00\x11\x08\x00\x01\x00\x01", 9);
  app1.resize(2998, 'x');
  const std::string with_exif = jpg.substr(0, 2) + "\xFF\xE1" + char(3000 >> 8) + char(3000 & 0xFF) + app1 + jpg.substr(2);
  EXPECT_EQ(image_header_size(with_exif), size);
  // A big-endian TIFF directory: ImageWidth LONG 70000, ImageLength SHORT 3.
  const std::string tiff = std::string("MM\x00\x2A", 4) + be32(8) + std::string("\x00\x02", 2) +
                           std::string("\x01\x00\x00\x04", 4) + be32(1) + be32(70000) +
                           std::string("\x01\x01\x00\x03", 4) + be32(1) + std::string("\x00\x03\x00\x00", 4) + be32(0);
  EXPECT_EQ(image_header_size(tiff), cv::Size(70000, 3));
  // PNM with comments between the numbers.
  EXPECT_EQ(image_header_size(std::string("P6\n# made by hand\n 12 # width\n34\n255\n")), cv::Size(12, 34));
}

TEST(ImageHeader, BrokenOrUnknownHeadersSayNothing) {
  for (const std::string& bytes :
       {std::string(), std::string("not an image"), std::string("\x89PNG\r\n\x1a\n", 8),
        png_header(0, 10), std::string("\xFF\xD8\xFF\xE0\x00", 5), std::string("\xFF\xD8\xFF\xDA\x00\x02", 6),
        std::string("BM"), std::string("II\x2A\x00\xFF\xFF\xFF\x7F", 8), std::string("P5 12"),
        std::string("P5 -3 4\n"), std::string("RIFF\0\0\0\0WEBPVP8 ", 16)}) {
    EXPECT_FALSE(image_header_size(bytes).has_value()) << ::testing::PrintToString(bytes);
  }
  const std::string png = encoded(".png", {20, 10});
  EXPECT_FALSE(image_header_size(png.substr(0, 20)).has_value());  // cut inside IHDR
  EXPECT_EQ(image_header_size(png.substr(0, 24)), cv::Size(20, 10));
}

TEST(FramePixels, LimitIs64MegapixelsWithAReadableMessage) {
  check_frame_pixels("a", 8000, 8000);  // exactly 64 MP
  check_frame_pixels("a", 7680, 4320);  // 8K UHD
  EXPECT_EQ(input_error([] { check_frame_pixels("big.png", 10000, 10000); }),
            "big.png: 10000x10000 pixels (100.0 MP) exceeds the 64 MP limit per frame");
  EXPECT_EQ(input_error([] { check_frame_pixels("wide.avi", 64001, 1000); }),
            "wide.avi: 64001x1000 pixels (64.0 MP) exceeds the 64 MP limit per frame");
}

TEST(FramePixels, ImageFilesAndSourcesAreRefusedFromTheHeaderBeforeDecoding) {
  testing::TempDir dir;
  const std::string big = (dir / "big.png").string();
  testing::write_text(big, png_header(10000, 10000));
  const std::string message = big + ": 10000x10000 pixels (100.0 MP) exceeds the 64 MP limit per frame";
  EXPECT_EQ(image_file_header_size(big), cv::Size(10000, 10000));
  EXPECT_EQ(input_error([&] { read_image_file(big, cv::IMREAD_COLOR); }), message);
  SourceOptions o;
  o.path = big;
  EXPECT_EQ(input_error([&] { open_source(o); }), message);  // at open: before any output exists

  // In a folder, a big image after a good one stops the run at its turn, naming the frame.
  testing::write_text(dir / "a.png", encoded(".png", {32, 24}));
  o.path = dir.path().string();
  auto source = open_source(o);
  Frame frame;
  ASSERT_TRUE(source->read(frame));
  EXPECT_EQ(frame.image.size(), cv::Size(32, 24));
  EXPECT_EQ(input_error([&] { source->read(frame); }), message + " (frame 1)");
  // ... and at open when it is the first frame wanted.
  o.start = 1;
  EXPECT_EQ(input_error([&] { open_source(o); }), message);
}

TEST(FrameSource, VideoWithoutAFrameIsAnInputErrorAtOpen) {
  testing::TempDir dir;
  const std::string path = (dir / "none.avi").string();
  {
    cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, cv::Size(64, 48));
    ASSERT_TRUE(writer.isOpened());
  }
  SourceOptions o;
  o.path = path;
  EXPECT_EQ(input_error([&] { open_source(o); }), "video has no decodable frame: " + path);

  // Frame 0, decoded at open, is still delivered first, with --start and --every as before.
  {
    cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, cv::Size(64, 48));
    for (int i = 0; i < 5; ++i) writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 50, 0, 0)));
  }
  for (const int start : {0, 1}) {
    o.start = start;
    o.every = 2;
    auto source = open_source(o);
    std::vector<int> indices;
    std::vector<double> blue;
    for (Frame f; source->read(f);) {
      indices.push_back(f.index);
      blue.push_back(cv::mean(f.image)[0]);
    }
    EXPECT_EQ(indices, start == 0 ? std::vector<int>({0, 2, 4}) : std::vector<int>({1, 3}));
    for (size_t i = 0; i < blue.size(); ++i) EXPECT_NEAR(blue[i], indices[i] * 50, 3) << indices[i];
  }
}

}  // namespace
}  // namespace bodyrec
