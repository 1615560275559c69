#ifndef TFW_TARGET_DEVICE_CONFIG_H
#define TFW_TARGET_DEVICE_CONFIG_H
/* The STReSS-like device the checks use: 10 x 10 at 1 kHz, +-50 um, 10 um per tick slew
 * (100000 units/s), 5 ms watchdog. */
#include "tactile_fw/device.h"

#define TFW_TEST_CONTACTORS 100u

static inline tfw_config tfw_test_stress_config(void) {
  tfw_config c;
  c.rows = 10;
  c.cols = 10;
  c.pitch_x_nm = 1000000;
  c.pitch_y_nm = 1000000;
  c.contactor_width_nm = 500000;
  c.contactor_height_nm = 500000;
  c.axis = 0;
  c.deflection_min = -500;
  c.deflection_max = 500;
  c.max_slew_per_s = 100000;
  c.rate_hz = 1000;
  c.max_rate_hz = 1000;
  c.watchdog_timeout_ms = 5;
  return c;
}

#endif /* TFW_TARGET_DEVICE_CONFIG_H */
