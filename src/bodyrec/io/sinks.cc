#include "bodyrec/io/sinks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

void make_parent_dirs(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw ProcessingError("cannot create folder " + parent.string() + ": " + ec.message());
}

}  // namespace

bool is_video_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".avi" || ext == ".mp4" || ext == ".mkv" || ext == ".mov";
}

JsonlWriter::JsonlWriter(const std::string& path) : path_(path) {
  if (path.empty() || path == "-") return;
  make_parent_dirs(path);
  file_ = std::make_unique<std::ofstream>(path, std::ios::trunc);
  if (!*file_) throw ProcessingError("cannot create " + path);
}

void JsonlWriter::write(const nlohmann::json& object) {
  std::ostream& out = file_ ? static_cast<std::ostream&>(*file_) : std::cout;
  out << json_text(object) << '\n';
  out.flush();
  if (!out) throw ProcessingError("cannot write to " + (file_ ? path_ : std::string("stdout")));
}

MotWriter::MotWriter(const std::string& path) : path_(path) {
  make_parent_dirs(path);
  out_.open(path, std::ios::trunc);
  if (!out_) throw ProcessingError("cannot create " + path);
  out_ << std::setprecision(6) << std::fixed;
}

void MotWriter::write(int frame, int id, const Box& box, double score) {
  // Values that print as zero are written as 0.00, never -0.00 (a tiny negative x or y).
  auto c = [](double v) { return std::abs(v) < 0.005 ? 0.0 : v; };
  out_ << frame + 1 << ',' << id << ',' << std::setprecision(2) << c(box.x) << ',' << c(box.y) << ','
       << c(box.width) << ',' << c(box.height) << ',' << std::setprecision(6) << score << ",-1,-1,-1\n";
}

void MotWriter::end_frame() {
  out_.flush();
  if (!out_) throw ProcessingError("cannot write to " + path_);
}

AnnotatedWriter::AnnotatedWriter(const std::string& path, double fps)
    : path_(path), fps_(fps > 0 ? fps : 25.0), is_video_(is_video_path(path)) {
  if (is_video_) {
    make_parent_dirs(path);
  } else {
    folder_.emplace(path);
  }
}

AnnotatedWriter::~AnnotatedWriter() { video_.release(); }

void AnnotatedWriter::write(int frame_index, const cv::Mat& image) {
  if (!is_video_) {
    const std::string file = folder_->file(frame_index);
    if (!cv::imwrite(file, image)) throw ProcessingError("cannot write " + file);
    return;
  }
  if (!video_.isOpened()) {
    std::string ext = fs::path(path_).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    const bool mp4 = ext == ".mp4";
    const int fourcc = mp4 ? cv::VideoWriter::fourcc('m', 'p', '4', 'v') : cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
    if (!video_.open(path_, fourcc, fps_, image.size()))
      throw ProcessingError("cannot create video " + path_);
    size_ = image.size();
  }
  if (image.size() == size_) {
    video_.write(image);
    return;
  }
  // A video has one frame size (the writer silently drops frames of another): images of other sizes are
  // scaled to fit it, centred on black.
  const double s = std::min(static_cast<double>(size_.width) / image.cols, static_cast<double>(size_.height) / image.rows);
  const cv::Size fitted(std::max(1, cvRound(image.cols * s)), std::max(1, cvRound(image.rows * s)));
  cv::Mat canvas(size_, image.type(), cv::Scalar::all(0));
  cv::resize(image, canvas(cv::Rect((size_.width - fitted.width) / 2, (size_.height - fitted.height) / 2, fitted.width,
                                    fitted.height)),
             fitted, 0, 0, cv::INTER_AREA);
  video_.write(canvas);
}

}  // namespace bodyrec
