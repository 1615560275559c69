/* Device core: playout order, malformed frames, clamp and slew, watchdog, full FIFO. */
#include <string.h>

#include "check.h"
#include "device_config.h"
#include "tactile_fw/device.h"

static tfw_result send(tfw_device* dev, uint32_t seq, int16_t value, uint8_t flags) {
  int16_t v[TFW_TEST_CONTACTORS];
  for (unsigned i = 0; i < TFW_TEST_CONTACTORS; ++i) v[i] = value;
  uint8_t bytes[TFW_FRAME_BYTES(TFW_TEST_CONTACTORS)];
  size_t len = 0;
  tfw_encode_frame(seq, flags, v, TFW_TEST_CONTACTORS, bytes, sizeof bytes, &len);
  return tfw_device_receive(dev, bytes, len);
}

/* Deterministic pseudo-random numbers (Numerical Recipes LCG): no libc state on the target. */
static uint32_t next_random(uint32_t* state) {
  *state = *state * 1664525u + 1013904223u;
  return *state >> 8;
}

void device_checks(tfw_check_run* run) {
  static tfw_device dev;
  const tfw_config config = tfw_test_stress_config();
  CHECK(run, tfw_device_init(&dev, &config, NULL) == TFW_CONFIG_OK);
  CHECK(run, send(&dev, 1, 10, 0) == TFW_ERR_NOT_STARTED);
  CHECK(run, tfw_device_start(&dev, 0) == TFW_CONFIG_OK);

  /* In order, one per tick; 10 units is below the 100 units per tick slew limit. */
  CHECK(run, send(&dev, 1, 10, 0) == TFW_OK);
  CHECK(run, send(&dev, 2, 20, 0) == TFW_OK);
  tfw_device_tick(&dev);
  CHECK(run, tfw_device_outputs(&dev)[0] == 10);
  tfw_device_tick(&dev);
  CHECK(run, tfw_device_outputs(&dev)[99] == 20);

  /* Repeated sequence and a corrupted frame: counted by reason, never played. */
  CHECK(run, send(&dev, 2, 30, 0) == TFW_ERR_BAD_SEQUENCE);
  uint8_t bytes[TFW_FRAME_BYTES(TFW_TEST_CONTACTORS)];
  memset(bytes, 0xA5, sizeof bytes);
  CHECK(run, tfw_device_receive(&dev, bytes, sizeof bytes) == TFW_ERR_BAD_MAGIC);
  tfw_status s;
  tfw_device_status(&dev, &s);
  CHECK(run, s.malformed_total == 2 && s.rejected[TFW_ERR_BAD_SEQUENCE] == 1);
  CHECK(run, s.rejected[TFW_ERR_BAD_MAGIC] == 1 && s.frames_played == 2);

  /* Random targets far outside the range: the output never leaves [-500, 500] and never
   * moves more than 100 units (100000 units/s at 1 kHz) in one tick. */
  uint32_t rng = 12345u;
  int limits_held = 1;
  int16_t previous = tfw_device_outputs(&dev)[0];
  for (uint32_t seq = 3; seq < 500; ++seq) {
    const int16_t value = (int16_t)((int32_t)(next_random(&rng) % 4001u) - 2000);
    send(&dev, seq, value, 0);
    tfw_device_tick(&dev);
    const int16_t out = tfw_device_outputs(&dev)[0];
    const int32_t step = (int32_t)out - previous;
    limits_held &= out >= -500 && out <= 500 && step <= 100 && step >= -100;
    previous = out;
  }
  CHECK(run, limits_held);
  tfw_device_status(&dev, &s);
  CHECK(run, s.clamped_samples > 0 && s.slew_limited_samples > 0 && s.underruns == 0);

  /* Watchdog: from full deflection, neutral within 20 ms (20 ticks) of the last frame (5 ms
   * timeout plus 500 units at 100 per tick = 10 ticks). */
  for (uint32_t seq = 600; seq < 612; ++seq) {
    send(&dev, seq, 500, 0);
    tfw_device_tick(&dev);
  }
  CHECK(run, tfw_device_outputs(&dev)[0] == 500);
  for (int i = 0; i < 20; ++i) tfw_device_tick(&dev);
  CHECK(run, tfw_device_outputs(&dev)[0] == 0);
  tfw_device_status(&dev, &s);
  CHECK(run, s.watchdog_trips == 1);

  /* Full FIFO: refused as fifo_full, then the very same frame is accepted after a tick. */
  CHECK(run, tfw_device_start(&dev, 0) == TFW_CONFIG_OK);
  for (uint32_t seq = 1; seq <= TFW_FIFO_CAPACITY; ++seq) send(&dev, seq, 1, 0);
  CHECK(run, !tfw_device_can_receive(&dev));
  CHECK(run, send(&dev, TFW_FIFO_CAPACITY + 1u, 1, 0) == TFW_ERR_FIFO_FULL);
  tfw_device_tick(&dev);
  CHECK(run, send(&dev, TFW_FIFO_CAPACITY + 1u, 1, TFW_FLAG_END_OF_STREAM) == TFW_OK);
  for (unsigned i = 0; i < TFW_FIFO_CAPACITY + 30u; ++i) tfw_device_tick(&dev);
  tfw_device_status(&dev, &s);
  /* The end-of-stream flag ends the stream: idle ticks afterwards are no underruns. */
  CHECK(run, s.frames_played == TFW_FIFO_CAPACITY + 1u && s.underruns == 0);
  CHECK(run, s.overflows == 1 && s.watchdog_trips == 0 && s.state == TFW_STATE_IDLE);
}
