// Reading one image file with errors bodyrec can report: a missing, unreadable, empty or truncated file is
// an InputError naming it, found before the decoder runs. OpenCV's decoders print their own lines on stderr
// (libpng "Read Error", libjpeg "Premature end of JPEG file") and a truncated JPEG even decodes, grey below
// the cut; checking the file's end first keeps the error to bodyrec's one line and refuses half images.
#pragma once

#include <string>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// Decodes `path` with cv::imdecode `flags` (cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED, ...). Throws
// InputError "PATH: missing", "PATH: a directory, not an image", "PATH: cannot read (reason)",
// "PATH: empty file", "PATH: truncated PNG|JPEG file (...)", "PATH: cannot decode image" or, from the
// header before decoding (image_header.h), "PATH: WxH pixels (N MP) exceeds the 64 MP limit per frame".
cv::Mat read_image_file(const std::string& path, int flags);

// The reason `bytes` is an incomplete PNG or JPEG file ("" when complete or another format): a PNG must
// reach its IEND chunk, a JPEG its end-of-image marker after the first scan.
std::string truncated_image_reason(const std::string& bytes);

}  // namespace bodyrec
