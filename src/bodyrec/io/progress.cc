#include "bodyrec/io/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace bodyrec {

bool progress_on_terminal(bool quiet) { return !quiet && isatty(STDERR_FILENO); }

Progress::Progress(std::optional<int> total, bool quiet)
    : total_(total), enabled_(progress_on_terminal(quiet)),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() {
  if (drawn_) std::fputc('\n', stderr);
}

void Progress::update(int done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  drawn_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fps = elapsed > 0 ? done / elapsed : 0;
  if (total_ && *total_ > 0) {
    const int width = 30;
    const int filled = static_cast<int>(width * std::min(1.0, double(done) / *total_));
    const double eta = fps > 0 ? (*total_ - done) / fps : 0;
    std::fprintf(stderr, "\r[%.*s%*s] %d/%d frames  %.1f fps  ETA %d:%02d ", filled,
                 "##############################", width - filled, "", done, *total_, fps,
                 static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
  } else {
    std::fprintf(stderr, "\r%d frames  %.1f fps ", done, fps);
  }
  std::fflush(stderr);
}

}  // namespace bodyrec
