#include "stop_signal.h"

#include <csignal>

namespace bodyrec::cli {
namespace {

volatile std::sig_atomic_t g_stop = 0;
struct sigaction g_previous_int, g_previous_term;

void on_signal(int signal) {
  g_stop = 1;
  // The next one acts as if there were no handler.
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(signal, &fallback, nullptr);
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_stop = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
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
