// The frame loop of the commands that can read live: frames one by one from a reader, either directly
// (a file, as fast as it is processed, every frame) or, for a live device or --realtime, through a grabber
// thread that hands over at most `queue` frames and drops the oldest when processing falls behind
// (io/live_frames.h). The loop ends at the source's end, after max_frames, or on SIGINT/SIGTERM (while a
// StopOnSignal lives).
#pragma once

#include <chrono>
#include <functional>

#include "bodyrec/io/live_frames.h"
#include "stop_signal.h"

namespace bodyrec::cli {

struct FrameArrival {
  std::chrono::steady_clock::time_point at;       // when the frame was read (direct) or handed over (live)
  std::chrono::system_clock::time_point wall;     // the same on the wall clock
  long dropped = 0;                               // frames dropped so far
};

struct FrameLoopOptions {
  bool live = false;   // through the grabber thread
  bool pace = false;   // hand frames over at their own times (--realtime)
  size_t queue = 1;    // frames waiting for processing (live)
  int max_frames = -1; // -1 = all
};

struct FrameLoopStats {
  int frames = 0;        // frames processed
  long dropped = 0;      // frames dropped (live)
  bool stopped = false;  // ended by a signal
};

// `read(frame)` false at the end; `time_of(frame)` in seconds (for pace); `sink(frame, arrival)`.
// Exceptions of read and sink propagate (read's after the frames before it were processed).
template <class T>
FrameLoopStats run_frame_loop(const std::function<bool(T&)>& read, const std::function<double(const T&)>& time_of,
                              const FrameLoopOptions& options,
                              const std::function<void(T&, const FrameArrival&)>& sink) {
  FrameLoopStats stats;
  const auto more = [&] { return options.max_frames < 0 || stats.frames < options.max_frames; };
  if (!options.live) {
    for (T frame; more() && read(frame); ++stats.frames) {
      if (StopOnSignal::requested()) {
        stats.stopped = true;
        break;
      }
      sink(frame, {std::chrono::steady_clock::now(), std::chrono::system_clock::now(), 0});
    }
    return stats;
  }
  LiveFrames<T> live(read, {options.queue, options.pace}, time_of);
  Arrived<T> a;
  while (more()) {
    if (StopOnSignal::requested()) {
      stats.stopped = true;
      break;
    }
    const LiveNext next = live.next(a, std::chrono::milliseconds(50));
    if (next == LiveNext::kEnd) break;
    if (next == LiveNext::kTimeout) continue;
    sink(a.frame, {a.arrived, a.arrived_wall, a.dropped});
    ++stats.frames;
  }
  live.stop();
  stats.dropped = live.dropped();
  return stats;
}

}  // namespace bodyrec::cli
