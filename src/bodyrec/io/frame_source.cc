#include "bodyrec/io/frame_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/image_file.h"
#include "bodyrec/io/image_header.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Frame selection shared by every source: start, every, max_frames.
class Selection {
 public:
  explicit Selection(const SourceOptions& o) : o_(o) {}
  bool wanted(int index) const { return index >= o_.start && (index - o_.start) % o_.every == 0; }
  bool done() const { return o_.max_frames >= 0 && delivered_ >= o_.max_frames; }
  void delivered() { ++delivered_; }
  std::optional<int> count(std::optional<int> total) const {
    if (!total) return std::nullopt;
    int n = std::max(0, (*total - o_.start + o_.every - 1) / o_.every);
    if (o_.max_frames >= 0) n = std::min(n, o_.max_frames);
    return n;
  }

 private:
  SourceOptions o_;
  int delivered_ = 0;
};

class ImageListSource : public FrameSource {
 public:
  ImageListSource(std::vector<std::string> files, std::string description, const SourceOptions& o)
      : files_(std::move(files)), description_(std::move(description)), selection_(o) {
    next_ = o.start;
    // The first frame's size from its header, before the command creates any output; the others are
    // checked the same way as they are read.
    if (next_ < static_cast<int>(files_.size()))
      if (const auto size = image_file_header_size(files_[next_]))
        check_frame_pixels(files_[next_], size->width, size->height);
  }

  bool read(Frame& frame) override {
    while (!selection_.done() && next_ < static_cast<int>(files_.size())) {
      const int index = next_++;
      if (!selection_.wanted(index)) continue;
      const std::string& file = files_[index];
      cv::Mat image;
      try {
        image = read_image_file(file, cv::IMREAD_COLOR);
      } catch (const InputError& e) {
        throw InputError(std::string(e.what()) + " (frame " + std::to_string(index) + ")");
      }
      frame = Frame{image, index, 0.0, file};
      selection_.delivered();
      return true;
    }
    return false;
  }
  std::optional<double> fps() const override { return std::nullopt; }
  std::optional<int> frame_count() const override {
    return selection_.count(static_cast<int>(files_.size()));
  }
  std::string describe() const override { return description_; }

 private:
  std::vector<std::string> files_;
  std::string description_;
  Selection selection_;
  int next_ = 0;
};

class CaptureSource : public FrameSource {
 public:
  CaptureSource(cv::VideoCapture capture, std::string description, const SourceOptions& o, bool is_file)
      : capture_(std::move(capture)), description_(std::move(description)), selection_(o),
        is_file_(is_file) {
    const double f = capture_.get(cv::CAP_PROP_FPS);
    if (f > 0 && f < 1000) fps_ = f;
    check_frame_pixels(description_, static_cast<int64_t>(capture_.get(cv::CAP_PROP_FRAME_WIDTH)),
                       static_cast<int64_t>(capture_.get(cv::CAP_PROP_FRAME_HEIGHT)));
    if (is_file_) {
      const double n = capture_.get(cv::CAP_PROP_FRAME_COUNT);
      if (n > 0) total_ = static_cast<int>(n);
      // A video without one decodable frame is refused like an empty file, before any output exists.
      cv::Mat image;
      if (!capture_.read(image) || image.empty()) throw InputError("video has no decodable frame: " + description_);
      check_frame_pixels(description_, image.cols, image.rows);
      first_ = std::move(image);
    }
  }

  bool read(Frame& frame) override {
    cv::Mat image;
    while (!selection_.done()) {
      bool grabbed;
      if (next_ == 0 && !first_.empty()) {
        grabbed = true;
        image = first_;
        first_.release();
      } else {
        grabbed = selection_.wanted(next_) ? capture_.read(image) : capture_.grab();
      }
      const int index = next_++;
      if (!grabbed) {
        // A file that stops well before its announced length is truncated or corrupt, not finished.
        if (is_file_ && total_ && index < *total_ - 1)
          throw InputError(description_ + ": cannot decode frame " + std::to_string(index) + " of " +
                           std::to_string(*total_) + " (truncated or corrupt file)");
        return false;
      }
      if (!selection_.wanted(index)) continue;
      const double t = fps_ ? index / *fps_ : capture_.get(cv::CAP_PROP_POS_MSEC) / 1000.0;
      frame = Frame{image, index, t, description_ + "#" + std::to_string(index)};
      selection_.delivered();
      return true;
    }
    return false;
  }
  std::optional<double> fps() const override { return fps_; }
  std::optional<int> frame_count() const override {
    return is_file_ ? selection_.count(total_) : std::nullopt;
  }
  std::string describe() const override { return description_; }

 private:
  cv::VideoCapture capture_;
  std::string description_;
  Selection selection_;
  bool is_file_;
  int next_ = 0;
  std::optional<double> fps_;
  std::optional<int> total_;
  cv::Mat first_;  // a file's frame 0, read when it was opened
};

std::unique_ptr<FrameSource> open_video(const SourceOptions& o) {
  {
    std::ifstream probe(o.path, std::ios::binary);
    if (!probe) throw InputError("cannot read video file: " + o.path);
    if (probe.peek() == std::ifstream::traits_type::eof())
      throw InputError("video file is empty: " + o.path);
  }
  cv::VideoCapture capture(o.path, cv::CAP_FFMPEG);
  if (!capture.isOpened())
    throw InputError("cannot open " + o.path + " as a video (unknown format or corrupt file)");
  return std::make_unique<CaptureSource>(std::move(capture), o.path, o, true);
}

std::vector<std::string> image_files_in(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && is_image_path(it->path().string())) files.push_back(it->path());
  }
  if (ec) throw InputError("cannot list directory " + dir + ": " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

void SourceOptions::check() const {
  if (path.empty() && camera < 0) throw UsageError("no input: give a SOURCE path or --camera N");
  if (!path.empty() && camera >= 0) throw UsageError("give either a SOURCE path or --camera, not both");
  if (start < 0) throw OptionError("SourceOptions", "start", "must be >= 0 (got " + std::to_string(start) + ")");
  if (every < 1) throw OptionError("SourceOptions", "every", "must be >= 1 (got " + std::to_string(every) + ")");
  if (max_frames < -1) throw OptionError("SourceOptions", "max_frames", "must be >= 0, or -1 for all");
}

bool is_image_path(const std::string& path) {
  static const char* kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff",
                                      ".ppm", ".pgm", ".webp"};
  const std::string ext = lower_extension(path);
  return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                     [&](const char* e) { return ext == e; });
}

std::unique_ptr<FrameSource> open_image_list(std::vector<std::string> files, const std::string& description,
                                             const SourceOptions& options) {
  SourceOptions selection = options;  // the files are the input: only the frame selection is checked
  selection.path = description;
  selection.camera = -1;
  selection.check();
  return std::make_unique<ImageListSource>(std::move(files), description, options);
}

std::unique_ptr<FrameSource> open_source(const SourceOptions& o) {
  o.check();
  if (o.camera >= 0) {
    cv::VideoCapture capture(o.camera, cv::CAP_V4L2);
    if (!capture.isOpened())
      throw InputError("cannot open camera " + std::to_string(o.camera) + " (no such V4L2 device)");
    return std::make_unique<CaptureSource>(std::move(capture), "camera " + std::to_string(o.camera), o,
                                           false);
  }
  // cv::glob understands only '*' and '?' (in the file name); other paths, '[' included, are taken as is.
  if (o.path.find_first_of("*?") != std::string::npos) {
    std::vector<cv::String> matches;
    try {
      cv::glob(o.path, matches, false);
    } catch (const cv::Exception&) {
      matches.clear();  // the pattern's folder does not exist or cannot be read
    }
    std::vector<std::string> files;
    for (const auto& m : matches)
      if (is_image_path(m)) files.push_back(m);
    std::sort(files.begin(), files.end());
    if (files.empty()) throw InputError("no images match the pattern " + o.path);
    return std::make_unique<ImageListSource>(std::move(files), o.path, o);
  }
  std::error_code ec;
  if (!fs::exists(o.path, ec)) throw InputError("input not found: " + o.path);
  if (fs::is_directory(o.path, ec)) {
    auto files = image_files_in(o.path);
    if (files.empty()) throw InputError("no images in directory " + o.path);
    return std::make_unique<ImageListSource>(std::move(files), o.path, o);
  }
  if (is_image_path(o.path)) return std::make_unique<ImageListSource>(std::vector<std::string>{o.path}, o.path, o);
  return open_video(o);
}

}  // namespace bodyrec
