// SIGINT and SIGTERM end a run cleanly: while a StopOnSignal lives, they set a flag that the frame loops
// check between frames (outputs are then closed at their last whole line, the gallery keeps every commit,
// and the program exits 0). A second signal a second or more after the first ends the program at once, as
// without the handler (the same signal delivered twice at once counts as one).
#pragma once

namespace bodyrec::cli {

class StopOnSignal {
 public:
  StopOnSignal();   // installs the handlers (the previous ones are restored at destruction)
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  // Whether a signal asked to stop.
  static bool requested();
};

}  // namespace bodyrec::cli
