/*
 * libFuzzer target for the device's receive path: any byte string handed to the frame decoder
 * and to tfw_device_receive() must be classified (never crash, never read out of bounds under
 * ASan/UBSan), a frame the decoder accepts must re-encode to the same bytes, and nothing the
 * host sends may move an output outside the clamp range or faster than the slew limit.
 * A violated property aborts, which libFuzzer reports as a crash with the input saved.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tactile_fw/device.h"
#include "tactile_fw/wire.h"

/* A 4 x 4 device keeps valid frames short (48 bytes), so mutations often stay valid. */
static tfw_config fuzz_config(void) {
  tfw_config c;
  memset(&c, 0, sizeof c);
  c.rows = 4;
  c.cols = 4;
  c.pitch_x_nm = c.pitch_y_nm = 1000000;
  c.contactor_width_nm = c.contactor_height_nm = 500000;
  c.deflection_min = -500;
  c.deflection_max = 500;
  c.max_slew_per_s = 100000;
  c.rate_hz = 1000;
  c.max_rate_hz = 1000;
  c.watchdog_timeout_ms = 5;
  return c;
}

static void require(int ok) {
  if (!ok) abort();
}

static void check_decoder(const uint8_t* data, size_t size) {
  static int16_t deflection[TFW_MAX_CONTACTORS];
  static uint8_t again[TFW_MAX_FRAME_BYTES];
  tfw_frame_header header;
  const tfw_result r = tfw_decode_frame(data, size, &header, deflection, TFW_MAX_CONTACTORS);
  require(r >= TFW_OK && r < TFW_RESULT_COUNT);
  if (r != TFW_OK) return;
  size_t len = 0;
  require(tfw_encode_frame(header.sequence, header.flags, deflection, header.contactor_count, again,
                           sizeof again, &len) == TFW_OK);
  require(len == size && memcmp(again, data, size) == 0);
}

/* The input is also read as a stream of frames, each prefixed by a one-byte length, so that
 * sequences of frames (ordering, FIFO full, watchdog) are explored, not only single frames. */
static void check_device(const uint8_t* data, size_t size) {
  static tfw_device dev;
  const tfw_config config = fuzz_config();
  require(tfw_device_init(&dev, &config, NULL) == TFW_CONFIG_OK);
  require(tfw_device_start(&dev, 0) == TFW_CONFIG_OK);
  const int16_t step = (int16_t)(config.max_slew_per_s / config.rate_hz);
  int16_t previous[16] = {0};
  size_t at = 0;
  while (at < size) {
    const size_t len = data[at++];
    const size_t take = len < size - at ? len : size - at;
    const tfw_result r = tfw_device_receive(&dev, data + at, take);
    require(r >= TFW_OK && r < TFW_RESULT_COUNT);
    at += take;
    tfw_device_tick(&dev);
    const int16_t* out = tfw_device_outputs(&dev);
    for (int i = 0; i < 16; ++i) {
      require(out[i] >= config.deflection_min && out[i] <= config.deflection_max);
      require(out[i] - previous[i] <= step && previous[i] - out[i] <= step);
      previous[i] = out[i];
    }
  }
  tfw_status s;
  tfw_device_status(&dev, &s);
  require(s.frames_played <= s.frames_received);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  check_decoder(data, size);
  check_device(data, size);
  return 0;
}
