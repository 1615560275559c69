#pragma once
// Work that must not delay the frames in flight (a detector, a smoothing choice) runs in the
// scheduler's idle class: it takes only the CPU time the other threads leave. On two cores a
// detection at normal priority took one of the tracker's two workers away for tens of
// milliseconds and held every frame behind it late.

#if defined(__linux__)
#include <sched.h>
#endif

namespace tactile {

// Moves the calling thread (and the threads it starts later, which inherit its class) to the
// idle scheduling class; false where the system has none or refuses (the thread then runs as
// before).
inline bool lower_to_idle_priority() {
#if defined(__linux__)
  sched_param none{};
  none.sched_priority = 0;
  return sched_setscheduler(0, SCHED_IDLE, &none) == 0;
#else
  return false;
#endif
}

}  // namespace tactile
