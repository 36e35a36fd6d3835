// The spool of events not yet delivered to the MQTT broker (issue 47): a bounded first-in first-out queue
// kept in a local file, so that events survive a broker outage and the end of the run that made them,
// and leave in the order they came.
//
// Files: SPOOL holds one JSON line per event ({"topic", "payload"}) in arrival order; SPOOL.sent holds how
// many of its first lines were delivered. A push appends its line at once (one write: it survives the
// process being killed; a power cut may lose the last lines the OS had not written); a delivery
// rewrites SPOOL.sent; when everything is delivered both start again empty, and SPOOL is compacted
// when most of it is delivered. A crash between a delivery and its record delivers that event again
// (at least once: subscribers drop repeats by event_id). Both files are created mode 0600: events say
// who was where. While a spool is open, its process holds an exclusive lock on SPOOL.lock (flock; mode
// 0600, left in place): two processes never share a spool, and `scrub` knows when a running one holds it.
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <string>

#include "bodyrec/core/error.h"

namespace bodyrec {

struct SpooledEvent {
  std::string topic, payload;
};

// Thrown when another process holds the spool open.
class SpoolInUse : public ProcessingError {
 public:
  using ProcessingError::ProcessingError;
};

// What `EventSpool::scrub` did to a spool file.
struct SpoolScrub {
  enum class State {
    kScrubbed,    // rewritten without the unwanted events (its owner and group kept)
    kInUse,       // a running process holds it (and withdraws what it must itself): left untouched
    kOtherOwner,  // another user's file and this process is not root: rewriting it would take it from them
  };
  State state = State::kScrubbed;
  size_t removed = 0;  // undelivered events taken out
};

// Not thread-safe: the publisher guards it with its lock.
class EventSpool {
 public:
  // Opens the spool at `path` (created when missing) and loads what an earlier run left undelivered.
  // `capacity` bounds the undelivered events; when it is full, a new event is dropped and counted
  // (the oldest, already waiting, keep their order). Lines that do not parse (a crash in the middle of a
  // write) are dropped and counted too. Waits up to `lock_wait_s` for another process's lock (a
  // `gallery forget` scrubbing it holds it for a moment), then SpoolInUse; ProcessingError when the
  // files cannot be read, created or written (an existing spool that cannot be read is never
  // overwritten). REQUIRES: capacity >= 1.
  explicit EventSpool(const std::string& path, size_t capacity, double lock_wait_s = 2.0);
  ~EventSpool();
  EventSpool(const EventSpool&) = delete;
  EventSpool& operator=(const EventSpool&) = delete;

  // Removes from the spool file at `path`, which no process holds open, every undelivered event for which
  // `unwanted` is true, and the delivered lines still kept at its head: afterwards none of their bytes
  // are in the file, and the files keep their owner and group (run as root, it gives them back). A spool
  // a running process holds is left as it is (kInUse), as is another user's spool when this process is
  // not root (kOtherOwner). InputError when there is no spool at `path`; ProcessingError when it cannot
  // be read or rewritten.
  static SpoolScrub scrub(const std::string& path, const std::function<bool(const SpooledEvent&)>& unwanted);

  // Queues an event and writes it to the file; false (and dropped() grows) when the spool is full.
  bool push(const SpooledEvent& event);
  // The oldest undelivered event. REQUIRES: !empty().
  const SpooledEvent& front() const { return queue_.front(); }
  // The front event was delivered: removed from the queue and recorded as delivered on disk.
  void pop();
  // Removes every undelivered event for which `unwanted` is true (not the front when `keep_front`: it is
  // on its way to the broker) and rewrites the file without them, so that their bytes leave the spool.
  // Returns how many were removed.
  size_t erase_if(const std::function<bool(const SpooledEvent&)>& unwanted, bool keep_front);

  bool empty() const { return queue_.empty(); }
  size_t size() const { return queue_.size(); }
  size_t capacity() const { return capacity_; }
  size_t dropped() const { return dropped_; }      // refused (full) or unreadable, since opened
  size_t recovered() const { return recovered_; }  // undelivered events found when opened
  const std::string& path() const { return path_; }

 private:
  void load();
  void write_sent(size_t lines);
  void append(const std::string& line);
  void compact();

  std::string path_;
  int lock_fd_ = -1;  // holds the flock on path_ + ".lock"
  size_t capacity_;
  std::deque<SpooledEvent> queue_;
  size_t sent_ = 0;  // delivered lines at the head of the file
  size_t dropped_ = 0, recovered_ = 0;
};

}  // namespace bodyrec
