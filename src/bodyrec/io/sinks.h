// Output sinks. Each writes and flushes per frame, so that when a run stops on an error everything
// processed so far is on disk and valid (whole JSON lines, whole MOT rows, a finalised video).
#pragma once

#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <opencv2/videoio.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/io/frame_folder.h"

namespace bodyrec {

// JSON Lines: one object per line, to a file or to stdout (path "" or "-").
class JsonlWriter {
 public:
  explicit JsonlWriter(const std::string& path);  // throws ProcessingError if it cannot be created
  void write(const nlohmann::json& object);
  bool to_stdout() const { return !file_; }

 private:
  std::unique_ptr<std::ofstream> file_;
  std::string path_;
};

// MOTChallenge text: frame,id,x,y,w,h,score,-1,-1,-1 with 1-based frames.
class MotWriter {
 public:
  explicit MotWriter(const std::string& path);
  // `frame` is 0-based; written 1-based. `id` is -1 for untracked detections.
  void write(int frame, int id, const Box& box, double score);
  void end_frame();  // flush

 private:
  std::ofstream out_;
  std::string path_;
};

// Annotated frames: a video when the path ends in .avi/.mp4/.mkv/.mov, else a directory of PNG files
// named NNNNNN.png by frame index. The video is opened on the first frame (its size) and finalised in
// the destructor; a later frame of another size (images of different sizes) is scaled to fit the video's
// size, centred on black, so that every frame is in the video.
class AnnotatedWriter {
 public:
  AnnotatedWriter(const std::string& path, double fps);
  ~AnnotatedWriter();
  void write(int frame_index, const cv::Mat& image);
  const std::string& path() const { return path_; }
  // A folder's frame files from an earlier run that this run did not replace (FrameFolder::stale_note);
  // "" for a video or when there are none.
  std::string stale_note() const { return folder_ ? folder_->stale_note() : ""; }

 private:
  std::string path_;
  double fps_;
  bool is_video_;
  std::optional<FrameFolder> folder_;
  cv::VideoWriter video_;
  cv::Size size_;  // the video's frame size
};

// True when `path` names a video file by its extension.
bool is_video_path(const std::string& path);

}  // namespace bodyrec
