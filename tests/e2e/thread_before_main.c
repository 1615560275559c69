// Preloaded (LD_PRELOAD) into `tactile` by the stop tests: like OpenBLAS's threaded build, it
// starts a thread before main() that leaves SIGINT and SIGTERM unblocked, so that the kernel may
// give a signal sent to the process to a thread the program did not start. Its name,
// "before-main", lets a test see that it runs.
#define _GNU_SOURCE
#include <pthread.h>
#include <unistd.h>

static void* idle(void* unused) {
  (void)unused;
  for (;;) pause();
  return 0;
}

__attribute__((constructor)) static void start_thread_before_main(void) {
  pthread_t thread;
  if (pthread_create(&thread, 0, idle, 0) == 0) {
    pthread_setname_np(thread, "before-main");
    pthread_detach(thread);
  }
}
