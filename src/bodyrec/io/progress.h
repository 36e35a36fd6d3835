// A progress line on stderr for long runs (frames done, fps, ETA), drawn only when stderr is a terminal
// and not asked to be quiet.
#pragma once

#include <chrono>
#include <optional>

namespace bodyrec {

class Progress {
 public:
  Progress(std::optional<int> total, bool quiet);
  ~Progress();  // ends the line
  void update(int frames_done);

 private:
  std::optional<int> total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace bodyrec
