#include "bodyrec/io/image_file.h"

#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

namespace bodyrec {
namespace {

using testing::contains;
using testing::input_error;

std::string encoded(const char* ext, std::vector<int> params = {}) {
  cv::Mat image(60, 80, CV_8UC3);
  cv::RNG(3).fill(image, cv::RNG::UNIFORM, 0, 256);
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes, params));
  return std::string(bytes.begin(), bytes.end());
}

TEST(ImageFile, CompleteFilesPassAndCutFilesAreTruncated) {
  for (const std::string& whole : {encoded(".png"), encoded(".jpg"), encoded(".jpg", {cv::IMWRITE_JPEG_PROGRESSIVE, 1})}) {
    EXPECT_EQ(broken_image_reason(whole), "");
    EXPECT_EQ(broken_image_reason(whole + "trailing bytes after the end"), "");  // some writers append data
    for (const size_t keep : {whole.size() / 2, whole.size() - 1, size_t{20}})
      EXPECT_TRUE(contains(broken_image_reason(whole.substr(0, keep)), "truncated")) << keep;
  }
  EXPECT_EQ(broken_image_reason(encoded(".png").substr(0, 100)),
            "truncated PNG file (100 bytes, no IEND chunk)");
  EXPECT_EQ(broken_image_reason(encoded(".jpg").substr(0, 100)),
            "truncated JPEG file (100 bytes, no image scan)");
  const std::string jpg = encoded(".jpg");
  EXPECT_EQ(broken_image_reason(jpg.substr(0, jpg.size() - 2)),
            "truncated JPEG file (" + std::to_string(jpg.size() - 2) + " bytes, no end-of-image marker)");
  // Other formats are left to the decoder.
  EXPECT_EQ(broken_image_reason(encoded(".bmp").substr(0, 100)), "");
  EXPECT_EQ(broken_image_reason(""), "");
}

TEST(ImageFile, APngChunkThatFailsItsCrcIsCorrupt) {
  const std::string whole = encoded(".png");
  const size_t idat = whole.find("IDAT") - 4;  // the chunk starts with its length
  for (const size_t at : {size_t{20}, idat + 30, whole.size() - 2}) {  // IHDR's height, image data, IEND's CRC
    std::string bad = whole;
    bad[at] = static_cast<char>(bad[at] ^ 1);
    const std::string chunk = at < idat ? "IHDR at byte 8" : at < whole.size() - 12 ? "IDAT at byte " + std::to_string(idat)
                                                                                    : "IEND at byte " + std::to_string(whole.size() - 12);
    EXPECT_EQ(broken_image_reason(bad), "corrupt PNG file (chunk " + chunk + " fails its CRC check)") << at;
  }
  std::string bad = whole;
  bad[idat] = static_cast<char>(0x80);  // a length above 2^31 - 1
  EXPECT_EQ(broken_image_reason(bad), "corrupt PNG file (chunk IDAT at byte " + std::to_string(idat) + " has an impossible length)");
}

TEST(ImageFile, BadFilesAreInputErrorsNamingTheFile) {
  testing::TempDir dir;
  const std::string path = (dir / "x.png").string();
  EXPECT_EQ(input_error([&] { read_image_file(path, cv::IMREAD_COLOR); }), path + ": missing");
  testing::write_text(path, "");
  EXPECT_EQ(input_error([&] { read_image_file(path, cv::IMREAD_COLOR); }), path + ": empty file");
  testing::write_text(path, "not an image at all");
  EXPECT_EQ(input_error([&] { read_image_file(path, cv::IMREAD_COLOR); }), path + ": cannot decode image");
  testing::write_text(path, encoded(".png").substr(0, 500));
  EXPECT_EQ(input_error([&] { read_image_file(path, cv::IMREAD_COLOR); }),
            path + ": truncated PNG file (500 bytes, no IEND chunk)");
  EXPECT_EQ(input_error([&] { read_image_file(dir.path().string(), cv::IMREAD_COLOR); }),
            dir.path().string() + ": a directory, not an image");
  testing::write_text(path, encoded(".png"));
  const cv::Mat image = read_image_file(path, cv::IMREAD_COLOR);
  EXPECT_EQ(image.size(), cv::Size(80, 60));
  EXPECT_EQ(image.type(), CV_8UC3);
}

}  // namespace
}  // namespace bodyrec
