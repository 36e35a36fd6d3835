// Frames from a live source handed from a grabber thread to the processing loop without ever queueing
// without bound: a camera or an RGB-D sensor (read as fast as it delivers), or a recording or video played
// at its own frame rate (`--realtime`, the same live path without a device). The hand-over holds at most
// `capacity` frames; a frame that arrives while it is full replaces the oldest, which is dropped and
// counted. The loop always gets the newest frames, is never more than `capacity` frames behind the source,
// and knows how many it missed.
//
//   LiveFrames<Frame> live([&](Frame& f) { return source->read(f); }, {.capacity = 1, .pace = true},
//                          [](const Frame& f) { return f.time_s; });
//   for (Arrived<Frame> a; live.next(a) == LiveNext::kFrame;) process(a.frame);   // a.arrived, a.dropped
//   live.dropped();
//
// Works for any frame type (io::Frame, rgbd::RgbdFrame). The reader runs on the grabber thread only.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "bodyrec/core/error.h"

namespace bodyrec {

struct LiveOptions {
  size_t capacity = 1;  // frames waiting for the loop; 1 or 2 keeps the latency at a frame or two
  // Hand each frame over at its own time (the first frame's arrival + its time after the first frame's),
  // as a device would deliver it, instead of as soon as it is read. A reader slower than the frame rate
  // delivers late (reading is not processing: nothing is dropped for it).
  bool pace = false;
  void check() const {
    if (capacity < 1) throw UsageError("live frames: capacity must be at least 1");
  }
};

template <class T>
struct Arrived {
  T frame;
  std::chrono::steady_clock::time_point arrived;       // when the grabber handed it over
  std::chrono::system_clock::time_point arrived_wall;  // the same on the wall clock (for output)
  long dropped = 0;  // frames dropped before this one was taken (the running total)
};

enum class LiveNext { kFrame, kEnd, kTimeout };

template <class T>
class LiveFrames {
 public:
  using Reader = std::function<bool(T&)>;          // next frame; false at the end; may throw
  using TimeOf = std::function<double(const T&)>;  // a frame's time in seconds (for pace)

  // Starts the grabber thread. REQUIRES time_of when options.pace.
  LiveFrames(Reader read, LiveOptions options = {}, TimeOf time_of = {})
      : read_(std::move(read)), options_(options), time_of_(std::move(time_of)) {
    options_.check();
    if (options_.pace && !time_of_) throw UsageError("live frames: pacing needs the frames' times");
    thread_ = std::thread([this] { grab(); });
  }
  ~LiveFrames() { stop(); }
  LiveFrames(const LiveFrames&) = delete;
  LiveFrames& operator=(const LiveFrames&) = delete;

  // The next frame, waiting at most `timeout` for it. kEnd once the source has ended (or stop() was called)
  // and every frame left in the hand-over was taken. A reader's exception is rethrown here, after the
  // frames read before it.
  LiveNext next(Arrived<T>& out, std::chrono::milliseconds timeout = std::chrono::hours(24)) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [this] { return !queue_.empty() || ended_; })) return LiveNext::kTimeout;
    if (queue_.empty()) {
      if (error_) {
        std::exception_ptr e = std::exchange(error_, nullptr);
        std::rethrow_exception(e);
      }
      return LiveNext::kEnd;
    }
    out = std::move(queue_.front());
    queue_.pop_front();
    out.dropped = dropped_;
    return LiveNext::kFrame;
  }

  // Ends the grabber after the read under way (a device read returns within its own timeout) and waits for
  // it. Frames still in the hand-over are left there (they are neither delivered by the grabber again nor
  // counted as dropped). Idempotent.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  long dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }
  long delivered() const {  // frames handed over so far (dropped ones included)
    std::lock_guard<std::mutex> lock(mutex_);
    return handed_;
  }

 private:
  void grab() {
    using Clock = std::chrono::steady_clock;
    Clock::time_point start;
    double first_time = 0;
    bool first = true;
    try {
      for (;;) {
        {
          std::lock_guard<std::mutex> lock(mutex_);
          if (stopping_) break;
        }
        Arrived<T> a;
        if (!read_(a.frame)) break;
        if (options_.pace) {
          const double t = time_of_(a.frame);
          if (first) {
            start = Clock::now();
            first_time = t;
          } else {
            const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(std::max(0.0, t - first_time)));
            std::unique_lock<std::mutex> lock(mutex_);
            if (wake_.wait_until(lock, due, [this] { return stopping_; })) break;
          }
          first = false;
        }
        a.arrived = Clock::now();
        a.arrived_wall = std::chrono::system_clock::now();
        {
          std::lock_guard<std::mutex> lock(mutex_);
          if (stopping_) break;
          if (queue_.size() >= options_.capacity) {
            queue_.pop_front();
            ++dropped_;
          }
          queue_.push_back(std::move(a));
          ++handed_;
        }
        ready_.notify_one();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ended_ = true;
    }
    ready_.notify_all();
  }

  Reader read_;
  LiveOptions options_;
  TimeOf time_of_;
  mutable std::mutex mutex_;
  std::condition_variable ready_, wake_;
  std::deque<Arrived<T>> queue_;
  long dropped_ = 0, handed_ = 0;
  bool stopping_ = false, ended_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace bodyrec
