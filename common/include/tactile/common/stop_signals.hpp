#pragma once
// SIGINT and SIGTERM as a request to stop, not as the end of the process: while a StopSignals
// lives, both signals are blocked and queue on a descriptor that loops poll between steps (a
// player between frames, a server between datagrams). So a loop stops where it is safe to (the
// device ramped back to rest, the summary printed, temporary files removed by their owners'
// destructors) with no signal handler and no state shared with one. The command then exits
// with exit_code(signal): 130 for SIGINT, 143 for SIGTERM, as a shell reports a process ended
// by that signal.

#include <signal.h>

namespace tactile {

class StopSignals {
 public:
  // Blocks SIGINT and SIGTERM in the calling thread; threads it starts afterwards inherit the
  // block, so create this before any thread that should not receive them (a thread started
  // before can still be chosen by the kernel and end the process as before; `tactile` blocks
  // both before the libraries' initialisers run, so that their threads never take them, see
  // tools/tactile/main.cpp). A signal the process ignores (SIG_IGN, e.g. a background job's
  // SIGINT) stays ignored: it is neither blocked nor watched. Throws std::runtime_error with
  // the OS's reason when the descriptor cannot be made.
  StopSignals();
  // Restores the signal mask: a signal that arrived and was not taken by received() is then
  // delivered as usual (its handler, or the default action that ends the process).
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // Readable (POLLIN) once a stop was requested; stays readable until received() takes it.
  int fd() const { return fd_; }
  // The first signal that asked to stop (SIGINT or SIGTERM), 0 while none has; never waits.
  int received();

 private:
  int fd_ = -1;
  int received_ = 0;
  sigset_t old_mask_{};
};

// True when `stop_fd` (a StopSignals::fd(), or any descriptor that becomes readable to ask for a
// stop) is readable now; false for -1. Never waits and never takes the signal.
bool stop_requested(int stop_fd);

// The process exit code for a command stopped by `signal`: 128 + signal.
constexpr int exit_code_for_signal(int signal) {
  return 128 + signal;
}

// The name a person reads for one of the two stop signals StopSignals watches.
constexpr const char* stop_signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : "SIGTERM";
}

}  // namespace tactile
