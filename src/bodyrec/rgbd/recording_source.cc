#include "bodyrec/rgbd/recording_source.h"

#include <algorithm>

#include "bodyrec/core/error.h"

namespace bodyrec {

RecordingFrameSource::RecordingFrameSource(const std::string& dir, const SourceOptions& options)
    : reader_(dir), options_(options) {
  options_.path = dir;
  options_.camera = -1;
  options_.check();
  if (!reader_.meta().streams.color) throw InputError(dir + ": recording has no colour stream");
  next_ = options_.start;
}

std::optional<int> RecordingFrameSource::frame_count() const {
  const int available = std::max(0, reader_.frame_count() - options_.start);
  const int n = (available + options_.every - 1) / options_.every;
  return options_.max_frames >= 0 ? std::min(n, options_.max_frames) : n;
}

bool RecordingFrameSource::read(Frame& frame) {
  if (next_ >= reader_.frame_count() || (options_.max_frames >= 0 && delivered_ >= options_.max_frames)) return false;
  const RgbdFrame f = reader_.read_frame(next_);
  frame.image = f.color;
  frame.index = f.index;
  frame.time_s = f.time_s;
  frame.name = reader_.dir() + "#" + std::to_string(f.index);
  next_ += options_.every;
  ++delivered_;
  return true;
}

}  // namespace bodyrec
