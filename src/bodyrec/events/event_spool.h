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
// who was where.
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <string>

namespace bodyrec {

struct SpooledEvent {
  std::string topic, payload;
};

// Not thread-safe: the publisher guards it with its lock.
class EventSpool {
 public:
  // Opens the spool at `path` (created when missing) and loads what an earlier run left undelivered.
  // `capacity` bounds the undelivered events; when it is full, a new event is dropped and counted
  // (the oldest, already waiting, keep their order). Lines that do not parse (a crash in the middle of a
  // write) are dropped and counted too. ProcessingError when the files cannot be created or written.
  // REQUIRES: capacity >= 1.
  EventSpool(const std::string& path, size_t capacity);

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
  void write_sent(size_t lines);
  void append(const std::string& line);
  void compact();

  std::string path_;
  size_t capacity_;
  std::deque<SpooledEvent> queue_;
  size_t sent_ = 0;  // delivered lines at the head of the file
  size_t dropped_ = 0, recovered_ = 0;
};

}  // namespace bodyrec
