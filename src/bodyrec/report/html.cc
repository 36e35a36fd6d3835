#include "bodyrec/report/html.h"

#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace bodyrec::report {

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += k[(v >> 6) & 63];
    out += k[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = bytes[i] << 16;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += k[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string jpeg_data_uri(const cv::Mat& image, int max_width, int quality) {
  cv::Mat shown = image;
  if (image.cols > max_width) {
    const double s = static_cast<double>(max_width) / image.cols;
    cv::resize(image, shown, cv::Size(), s, s, cv::INTER_AREA);
  }
  std::vector<unsigned char> jpeg;
  cv::imencode(".jpg", shown, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality});
  return "data:image/jpeg;base64," + base64(jpeg);
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       int numeric_from) {
  std::string out = "<table><thead><tr>";
  for (size_t i = 0; i < header.size(); ++i)
    out += std::string(static_cast<int>(i) >= numeric_from ? "<th class=\"num\">" : "<th>") +
           html_escape(header[i]) + "</th>";
  out += "</tr></thead><tbody>";
  for (const auto& row : rows) {
    out += "<tr>";
    for (size_t i = 0; i < row.size(); ++i)
      out += std::string(static_cast<int>(i) >= numeric_from ? "<td class=\"num\">" : "<td>") +
             html_escape(row[i]) + "</td>";
    out += "</tr>";
  }
  return out + "</tbody></table>";
}

std::string html_legend(const std::vector<std::pair<std::string, std::string>>& colour_and_label) {
  std::string out = "<div class=\"legend\">";
  for (const auto& [colour, label] : colour_and_label)
    out += "<span><i style=\"background:" + html_escape(colour) + "\"></i>" + html_escape(label) + "</span>";
  return out + "</div>";
}

std::string fmt(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace bodyrec::report
