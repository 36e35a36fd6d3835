// HTML building blocks for the self-contained report: escaping, embedded JPEG images, small tables.
// Everything the report shows goes through these so that text from runs (labels, file names) can never
// become markup.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec::report {

// Escapes &, <, >, " and ' so `text` is safe inside element content and quoted attribute values.
std::string html_escape(const std::string& text);

// "data:image/jpeg;base64,..." of `image` (BGR or grey 8-bit), first shrunk to at most `max_width`
// pixels wide (aspect kept). REQUIRES: non-empty image.
std::string jpeg_data_uri(const cv::Mat& image, int max_width = 640, int quality = 85);

// Standard base64 (RFC 4648, with padding).
std::string base64(const std::vector<unsigned char>& bytes);

// A table: the header cells and rows are escaped text. `numeric_from` = first column right-aligned.
std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       int numeric_from = 1);

// A legend line: a coloured square (CSS colour) and escaped label per item.
std::string html_legend(const std::vector<std::pair<std::string, std::string>>& colour_and_label);

// printf-style number formatting ("%.3f" -> "0.123").
std::string fmt(double value, int decimals = 2);

}  // namespace bodyrec::report
