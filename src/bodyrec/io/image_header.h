// An image's size from its file header, without decoding, and the pixel limit per frame. A frame larger
// than the limit would take gigabytes and minutes per step before anything is written, so every frame
// reader refuses it from the header (image files) or the capture's size (videos, cameras) at once.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

#include <opencv2/core/types.hpp>

namespace bodyrec {

// The most pixels a frame may have: 64 MP (64 million; 8K UHD is 33.2 MP).
constexpr int64_t kMaxFramePixels = 64'000'000;

// "WxH pixels (N.N MP) exceeds the 64 MP limit per frame" when width x height is above kMaxFramePixels,
// else "".
std::string frame_pixels_problem(int64_t width, int64_t height);

// Throws InputError "WHAT: " + frame_pixels_problem(width, height) when that is not "".
void check_frame_pixels(const std::string& what, int64_t width, int64_t height);

// Width and height read from the header at the start of `in`: PNG (IHDR), JPEG (the first SOFn frame
// header, after any EXIF or ICC segments), BMP, TIFF (the first image's tags), PBM/PGM/PPM and WebP (VP8,
// VP8L, VP8X). nullopt for another format or a header too short or too broken to say (the decoder then
// reports the file). Reads only as far as the size; `in` is left positioned anywhere.
std::optional<cv::Size> image_header_size(std::istream& in);
std::optional<cv::Size> image_header_size(const std::string& bytes);

// The same from the file at `path`; nullopt as well when it cannot be opened.
std::optional<cv::Size> image_file_header_size(const std::string& path);

}  // namespace bodyrec
