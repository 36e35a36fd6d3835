#include "stop_signal.h"

#include <csignal>
#include <ctime>

namespace bodyrec::cli {
namespace {

volatile std::sig_atomic_t g_stop = 0;
struct sigaction g_previous_int, g_previous_term;
double g_first_s = 0;  // monotonic time of the first signal (written by the handler only; handlers do not nest)

double now_s() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
  return static_cast<double>(t.tv_sec) + t.tv_nsec * 1e-9;
}

void on_signal(int signal) {
  if (!g_stop) {
    g_stop = 1;
    g_first_s = now_s();
    return;
  }
  // A signal sent twice at once (e.g. `timeout` signals the process and then its group) is one request; a
  // second one a second later ends the program at once, as without the handler.
  if (now_s() - g_first_s < 1.0) return;
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(signal, &fallback, nullptr);
  raise(signal);
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_stop = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);  // the handler runs for one signal at a time
  sigaddset(&action.sa_mask, SIGTERM);
  action.sa_flags = SA_RESTART;  // reads and writes under way finish; the loops check the flag
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

StopOnSignal::~StopOnSignal() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool StopOnSignal::requested() { return g_stop != 0; }

}  // namespace bodyrec::cli
