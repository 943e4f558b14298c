// SIGINT and SIGTERM while rill-trace renders (Interrupt.h).
#include "Interrupt.h"

#include <signal.h>

#include <csignal>

#include "rill/rt/scene/OutputFile.h"

namespace trace_cli {

namespace {

volatile std::sig_atomic_t g_signal = 0;
struct sigaction g_old_int {
}, g_old_term{};
bool g_int_set = false, g_term_set = false;

// Async-signal-safe only: a flag, unlink, signal and raise.
void on_signal(int sig) {
  if (g_signal == 0) {
    g_signal = sig;
    return;
  }
  // A second signal: the user does not want to wait for the pass or the save in flight.
  rt::remove_partial_output();
  std::signal(sig, SIG_DFL);
  std::raise(sig);  // delivered when this handler returns (the signal is blocked in it)
}

bool install(int sig, struct sigaction& old) {
  if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return false;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  // A system call the signal lands in (a wait, a write) goes on rather than failing with EINTR.
  sa.sa_flags = SA_RESTART;
  return sigaction(sig, &sa, nullptr) == 0;
}

}  // namespace

InterruptGuard::InterruptGuard() {
  g_signal = 0;
  g_int_set = install(SIGINT, g_old_int);
  g_term_set = install(SIGTERM, g_old_term);
}

InterruptGuard::~InterruptGuard() {
  if (g_int_set) sigaction(SIGINT, &g_old_int, nullptr);
  if (g_term_set) sigaction(SIGTERM, &g_old_term, nullptr);
}

int interrupted() {
  return g_signal;
}

const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

int interrupted_status(int sig) {
  return 128 + sig;
}

}  // namespace trace_cli
