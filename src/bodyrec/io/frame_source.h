// Frame sources: where images come from. One interface over a video file, a single image, a directory of
// images (sorted by name), a glob pattern, and a live camera (V4L2 through OpenCV).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

struct Frame {
  cv::Mat image;          // BGR, 8-bit
  int index = 0;          // 0-based index in the underlying source (before --start/--every)
  double time_s = 0.0;    // timestamp in seconds from the source start (index / fps for files)
  std::string name;       // file name for image sources, "path#index" for videos
};

// What to read and which frames to keep.
struct SourceOptions {
  std::string path;            // video, image, directory or glob; empty when camera >= 0
  int camera = -1;             // camera index, or -1
  int start = 0;               // first frame index to deliver
  int max_frames = -1;         // stop after delivering this many frames; -1 = all
  int every = 1;               // deliver every Nth frame from `start`
  void check() const;          // throws UsageError on inconsistent values
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Reads the next frame to deliver. Returns false at the end of the source.
  // Throws InputError when a frame cannot be decoded (naming the file and frame).
  virtual bool read(Frame& frame) = 0;
  // Frames per second of the source if known (videos, cameras), else nullopt.
  virtual std::optional<double> fps() const = 0;
  // Total frames the source will deliver if known (after start/every/max_frames), else nullopt.
  virtual std::optional<int> frame_count() const = 0;
  // Human-readable description ("video vtest.avi", "camera 0", ...), used in messages.
  virtual std::string describe() const = 0;
};

// Opens a source. Throws InputError (naming the path) when it is missing, unreadable, of an unknown
// kind, an empty directory or a glob matching nothing; UsageError on bad options.
std::unique_ptr<FrameSource> open_source(const SourceOptions& options);

// The image files `files` in the given order as one source (frame i = files[i]), with --start, --every and
// --max-frames applied; `description` names it in messages. A file that cannot be decoded is an InputError
// when it is read. REQUIRES: files is not empty.
std::unique_ptr<FrameSource> open_image_list(std::vector<std::string> files, const std::string& description,
                                             const SourceOptions& options);

// True when the path's extension is an image format OpenCV reads (png, jpg, jpeg, bmp, tif, tiff, ppm,
// pgm, webp), case-insensitive.
bool is_image_path(const std::string& path);

}  // namespace bodyrec
