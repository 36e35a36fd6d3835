// Reading one image file with errors bodyrec can report: a missing, unreadable, empty or truncated file, or
// a PNG whose chunk fails its CRC, is an InputError naming it, found before the decoder runs. OpenCV's
// decoders print their own lines on stderr (libpng "Read Error", "IDAT: CRC error", libjpeg "Premature end
// of JPEG file") and a truncated JPEG even decodes, grey below the cut; checking the file first keeps the
// error to bodyrec's one line and refuses half images. (A JPEG corrupt inside its scan has no checksum:
// libjpeg may still print its warning.)
#pragma once

#include <string>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// Decodes `path` with cv::imdecode `flags` (cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED, ...). Throws
// InputError "PATH: missing", "PATH: a directory, not an image", "PATH: cannot read (reason)",
// "PATH: empty file", "PATH: truncated PNG|JPEG file (...)", "PATH: corrupt PNG file (chunk T at byte N
// fails its CRC check)", "PATH: cannot decode image" or, from the
// header before decoding (image_header.h), "PATH: WxH pixels (N MP) exceeds the 64 MP limit per frame".
cv::Mat read_image_file(const std::string& path, int flags);

// The reason `bytes` is a broken PNG or JPEG file ("" when whole or another format): a PNG must reach its
// IEND chunk with every chunk's CRC right, a JPEG its end-of-image marker after the first scan.
std::string broken_image_reason(const std::string& bytes);

}  // namespace bodyrec
