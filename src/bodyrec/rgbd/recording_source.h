// A recording's colour stream as an ordinary FrameSource, so the 2-D pipeline (detect, track) runs on
// RGB-D recordings, including synthetic ones, unchanged.
#pragma once

#include <memory>
#include <string>

#include "bodyrec/io/frame_source.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

class RecordingFrameSource : public FrameSource {
 public:
  // Opens the recording. InputError when it has no colour stream (or cannot be read); UsageError on bad
  // frame selection options (start, every, max_frames of `options` apply; its path is ignored).
  RecordingFrameSource(const std::string& dir, const SourceOptions& options = {});
  bool read(Frame& frame) override;
  std::optional<double> fps() const override { return reader_.meta().fps; }
  std::optional<int> frame_count() const override;
  std::string describe() const override { return "recording " + reader_.dir(); }

 private:
  RecordingReader reader_;
  SourceOptions options_;
  int next_ = 0, delivered_ = 0;
};

}  // namespace bodyrec
