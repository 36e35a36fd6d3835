#include "bodyrec/events/event_spool.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <thread>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

namespace {

// Writes `text` as the whole content of `path` (mode 0600), through a temporary file and a rename so a
// crash leaves the old or the new content.
void replace_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) throw ProcessingError(tmp + ": cannot write the event spool: " + std::strerror(errno));
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int saved = errno;
  ::close(fd);
  if (!ok) throw ProcessingError(tmp + ": cannot write the event spool: " + std::strerror(saved));
  if (::rename(tmp.c_str(), path.c_str()) != 0)
    throw ProcessingError(path + ": cannot write the event spool: " + std::strerror(errno));
}

// The open descriptor of PATH.lock under an exclusive flock, or -1 when another process still holds it
// after `wait_s` seconds.
int lock_spool(const std::string& path, double wait_s) {
  const std::string file = path + ".lock";
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) throw ProcessingError(file + ": cannot create the event spool's lock: " + std::strerror(errno));
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int saved = errno;
    if (saved == EWOULDBLOCK && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    ::close(fd);
    if (saved == EWOULDBLOCK) return -1;
    throw ProcessingError(file + ": cannot lock the event spool: " + std::strerror(saved));
  }
  return fd;
}

// Gives the spool's files back to `owner` (scrub run as root rewrote them as root). Files that are not
// there are skipped.
void give_back(const std::string& path, const struct stat& owner) {
  for (const std::string& file : {path, path + ".sent", path + ".lock"})
    if (::chown(file.c_str(), owner.st_uid, owner.st_gid) != 0 && errno != ENOENT)
      throw ProcessingError(file + ": cannot give the event spool back to its owner: " + std::strerror(errno));
}

}  // namespace

EventSpool::EventSpool(const std::string& path, size_t capacity, double lock_wait_s) : path_(path), capacity_(capacity) {
  if (capacity_ == 0) throw UsageError("event spool capacity must be at least 1");
  lock_fd_ = lock_spool(path_, lock_wait_s);
  if (lock_fd_ < 0)
    throw SpoolInUse(path_ + ": the event spool is in use by another process (give each run its own --events-spool)");
  try {
    load();
  } catch (...) {
    ::close(lock_fd_);
    throw;
  }
}

EventSpool::~EventSpool() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

SpoolScrub EventSpool::scrub(const std::string& path, const std::function<bool(const SpooledEvent&)>& unwanted) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) throw InputError(path + ": no event spool there");
  SpoolScrub result;
  const bool root = ::geteuid() == 0;
  if (!root && st.st_uid != ::geteuid()) {
    result.state = SpoolScrub::State::kOtherOwner;
    return result;
  }
  try {
    // Opening compacts: the delivered lines leave the file whatever is removed. No wait: a process that
    // holds the lock is a running reid, which withdraws erased users' events itself.
    EventSpool spool(path, std::numeric_limits<size_t>::max(), 0.0);
    result.removed = spool.erase_if(unwanted, false);
  } catch (const SpoolInUse&) {
    result.state = SpoolScrub::State::kInUse;
    return result;
  }
  if (root && st.st_uid != 0) give_back(path, st);
  return result;
}

void EventSpool::load() {
  {
    std::ifstream sent(path_ + ".sent");
    long long n = 0;
    if (sent >> n && n > 0) sent_ = static_cast<size_t>(n);
  }
  std::ifstream in(path_);
  // A spool that is there but cannot be read (another owner's file) must not be taken for an empty one:
  // compact() below would overwrite its events.
  const int open_errno = errno;
  if (!in && ::access(path_.c_str(), F_OK) == 0)
    throw ProcessingError(path_ + ": cannot read the event spool: " + std::strerror(open_errno));
  std::string line;
  size_t index = 0;
  while (std::getline(in, line)) {
    if (index++ < sent_) continue;
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("topic") || !j.contains("payload") ||
        !j["topic"].is_string() || !j["payload"].is_string() || queue_.size() >= capacity_) {
      ++dropped_;
      continue;
    }
    queue_.push_back({j["topic"].get<std::string>(), j["payload"].get<std::string>()});
  }
  recovered_ = queue_.size();
  // Start from a file holding exactly the queue: no delivered or unreadable lines before it.
  compact();
}

void EventSpool::write_sent(size_t lines) { replace_file(path_ + ".sent", std::to_string(lines) + "\n"); }

void EventSpool::append(const std::string& line) {
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
  if (fd < 0) throw ProcessingError(path_ + ": cannot write the event spool: " + std::strerror(errno));
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  const int saved = errno;
  ::close(fd);
  if (!ok) throw ProcessingError(path_ + ": cannot write the event spool: " + std::strerror(saved));
}

// The delivered count goes to 0 before the file loses its delivered lines: a crash in between delivers
// them again rather than skipping undelivered ones.
void EventSpool::compact() {
  std::string text;
  for (const SpooledEvent& e : queue_) text += nlohmann::json({{"topic", e.topic}, {"payload", e.payload}}).dump() + "\n";
  write_sent(0);
  replace_file(path_, text);
  sent_ = 0;
}

bool EventSpool::push(const SpooledEvent& event) {
  if (queue_.size() >= capacity_) {
    ++dropped_;
    return false;
  }
  append(nlohmann::json({{"topic", event.topic}, {"payload", event.payload}}).dump() + "\n");
  queue_.push_back(event);
  return true;
}

size_t EventSpool::erase_if(const std::function<bool(const SpooledEvent&)>& unwanted, bool keep_front) {
  std::deque<SpooledEvent> kept;
  for (size_t i = 0; i < queue_.size(); ++i)
    if ((keep_front && i == 0) || !unwanted(queue_[i])) kept.push_back(std::move(queue_[i]));
  const size_t removed = queue_.size() - kept.size();
  queue_ = std::move(kept);
  if (removed > 0) compact();
  return removed;
}

void EventSpool::pop() {
  queue_.pop_front();
  ++sent_;
  if (queue_.empty() || (sent_ >= 1024 && sent_ > queue_.size())) {
    compact();
  } else {
    write_sent(sent_);
  }
}

}  // namespace bodyrec
