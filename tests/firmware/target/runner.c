/*
 * Runs every firmware check and exits non-zero when one fails, so that CTest (host) or QEMU's
 * semihosting exit status (Cortex-M4) reports the result.
 */
#include <stdio.h>

#include "check.h"
#include "tactile_fw/device.h"
#include "tactile_fw/usb.h"

typedef struct {
  const char* name;
  void (*run)(tfw_check_run* run);
} suite;

int main(void) {
  const suite suites[] = {{"wire", wire_checks},
                          {"fifo", fifo_checks},
                          {"device", device_checks},
                          {"control", control_checks},
                          {"usb", usb_checks}};
  /* The device state is the firmware's whole RAM need (the caller owns it, no heap). */
  printf("tfw_device: %u bytes of RAM (FIFO of %u frames)\n", (unsigned)sizeof(tfw_device),
         (unsigned)TFW_FIFO_CAPACITY);
  printf("tfw_usb: %u bytes of RAM (two frame assembly buffers)\n", (unsigned)sizeof(tfw_usb));
  tfw_check_run total = {0, 0};
  for (unsigned i = 0; i < sizeof suites / sizeof suites[0]; ++i) {
    tfw_check_run run = {0, 0};
    suites[i].run(&run);
    printf("%-8s %3u checks, %u failed\n", suites[i].name, run.checks, run.failures);
    total.checks += run.checks;
    total.failures += run.failures;
  }
  printf("firmware checks: %u, failed: %u (%s)\n", total.checks, total.failures,
         total.failures == 0 ? "PASS" : "FAIL");
  return total.failures == 0 ? 0 : 1;
}
