/* Device information and status replies: documented byte positions and round trip. */
#include <string.h>

#include "check.h"
#include "device_config.h"
#include "tactile_fw/control.h"

void control_checks(tfw_check_run* run) {
  static tfw_device dev;
  const tfw_config config = tfw_test_stress_config();
  tfw_device_init(&dev, &config, NULL);
  uint8_t info[TFW_INFO_BYTES];
  CHECK(run, tfw_encode_info(&dev, info, sizeof info - 1) == 0);
  CHECK(run, tfw_encode_info(&dev, info, sizeof info) == TFW_INFO_BYTES);
  CHECK(run, info[2] == 10 && info[4] == 10);                           /* rows, cols */
  CHECK(run, info[6] == 0x0C && info[7] == 0xFE);                       /* -500 = 0xFE0C */
  CHECK(run, info[10] == 0xE8 && info[11] == 0x03);                     /* 1000 Hz */
  CHECK(run, info[12] == 0x40 && info[13] == 0x42 && info[14] == 0x0F); /* 1000000 nm */
  CHECK(run, memcmp(info + 36, TFW_FIRMWARE_VERSION, strlen(TFW_FIRMWARE_VERSION)) == 0);
  tfw_device_info decoded;
  CHECK(run, tfw_decode_info(info, sizeof info, &decoded) == TFW_OK);
  CHECK(run, decoded.config.deflection_min == -500 && decoded.config.pitch_y_nm == 1000000);
  CHECK(run, decoded.fifo_capacity == TFW_FIFO_CAPACITY);
  CHECK(run, tfw_decode_info(info, sizeof info - 1, &decoded) == TFW_ERR_BAD_LENGTH);

  tfw_device_start(&dev, 500);
  for (int i = 0; i < 7; ++i) tfw_device_tick(&dev);
  uint8_t status[TFW_STATUS_BYTES];
  CHECK(run, tfw_encode_status(&dev, status, sizeof status) == TFW_STATUS_BYTES);
  CHECK(run, status[0] == TFW_STATE_IDLE);
  CHECK(run, status[6] == 0xF4 && status[7] == 0x01); /* 500 Hz */
  CHECK(run, status[44] == 7);                        /* ticks */
  tfw_status_report report;
  CHECK(run, tfw_decode_status(status, sizeof status, &report) == TFW_OK);
  CHECK(run, report.status.ticks == 7 && report.rate_hz == 500);
  CHECK(run, tfw_decode_status(status, 95, &report) == TFW_ERR_BAD_LENGTH);
}
