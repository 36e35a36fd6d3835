// A progress line on stderr for long runs (frames done, fps, ETA), drawn only when stderr is a terminal
// and not asked to be quiet.
#pragma once

#include <chrono>
#include <optional>

namespace bodyrec {

// True when progress should be drawn: not asked to be quiet, and stderr is a terminal (in a file or a
// pipe, '\r' redraws would pile up as junk lines).
bool progress_on_terminal(bool quiet);

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
