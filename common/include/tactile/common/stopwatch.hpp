#pragma once
// Wall-clock and CPU time for the figures the commands print. On a shared machine wall time
// measures the load as much as the work; process CPU time (every thread) does not, so benchmarks
// report both.

#include <chrono>
#include <ctime>

namespace tactile {

// Seconds of wall-clock time since t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU seconds the whole process (every thread) has used so far; differences are what counts.
inline double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Wall and CPU seconds since construction (or the last restart).
class Stopwatch {
 public:
  Stopwatch() { restart(); }
  void restart() {
    wall0_ = std::chrono::steady_clock::now();
    cpu0_s_ = process_cpu_s();
  }
  double wall_s() const { return seconds_since(wall0_); }
  double cpu_s() const { return process_cpu_s() - cpu0_s_; }

 private:
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_s_ = 0;
};

}  // namespace tactile
