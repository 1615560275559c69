#ifndef TFW_TARGET_CHECK_H
#define TFW_TARGET_CHECK_H
/*
 * A minimal C test harness for the firmware checks: the same checks run on the host and on the
 * emulated Cortex-M4 (QEMU, output through semihosting), where GoogleTest is not available.
 * State is passed explicitly (no globals, as in the firmware itself).
 */
#include <stdint.h>
#include <stdio.h>

typedef struct {
  unsigned checks;
  unsigned failures;
} tfw_check_run;

/* Records one check; prints the failing expression with its place. Returns `ok`. */
static inline int tfw_check(tfw_check_run* run, int ok, const char* what, const char* file,
                            int line) {
  run->checks++;
  if (!ok) {
    run->failures++;
    printf("FAIL %s:%d: %s\n", file, line, what);
  }
  return ok;
}

#define CHECK(run, cond) tfw_check((run), (cond) ? 1 : 0, #cond, __FILE__, __LINE__)

/* One test suite per firmware part; each runs its checks on `run`. */
void wire_checks(tfw_check_run* run);
void fifo_checks(tfw_check_run* run);
void device_checks(tfw_check_run* run);
void control_checks(tfw_check_run* run);
void usb_checks(tfw_check_run* run);

#endif /* TFW_TARGET_CHECK_H */
