/*
 * libFuzzer target for the device's receive path: any byte string handed to the frame decoder
 * and to tfw_device_receive() must be classified (never crash, never read out of bounds under
 * ASan/UBSan), a frame the decoder accepts must re-encode to the same bytes, and nothing the
 * host sends may move an output outside the clamp range or faster than the slew limit.
 * The USB glue (bulk packets, HID reports, control requests) gets the same treatment.
 * A violated property aborts, which libFuzzer reports as a crash with the input saved.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "device_config.h" /* tests/firmware/target */
#include "tactile_fw/device.h"
#include "tactile_fw/usb.h"
#include "tactile_fw/wire.h"

/* The checks' test device cut to 4 x 4, so that valid frames are short (48 bytes) and
 * mutations often stay valid. */
static tfw_config fuzz_config(void) {
  tfw_config c = tfw_test_stress_config();
  c.rows = 4;
  c.cols = 4;
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

static int null_write(void* context, uint8_t ep, const uint8_t* data, uint16_t len) {
  (void)context;
  (void)ep;
  require(len == 0 || data != NULL);
  return 1;
}

static void null_stall(void* context, uint8_t ep) {
  (void)context;
  (void)ep;
}

static void null_ready(void* context, uint8_t ep, int ready) {
  (void)context;
  (void)ep;
  (void)ready;
}

/* The USB glue reads the input as a script: each step's first byte picks bulk packet, HID
 * report, control request or tick, the next byte a length. Whatever the host does through
 * USB (including set-limits requests), the outputs stay within the hardware's limits. */
static void check_usb(const uint8_t* data, size_t size) {
  static tfw_device dev;
  static tfw_usb usb;
  const tfw_config config = fuzz_config();
  require(tfw_device_init(&dev, &config, NULL) == TFW_CONFIG_OK);
  const tfw_usb_dcd dcd = {NULL, null_write, null_stall, null_ready};
  tfw_usb_init(&usb, &dev, &dcd, TFW_USB_FULL_SPEED, "fuzz");
  size_t at = 0;
  while (at + 2 <= size) {
    const uint8_t op = data[at] & 3u;
    const size_t want = data[at + 1];
    at += 2;
    const size_t n = want < size - at ? want : size - at;
    if (op == 0) tfw_usb_bulk_out(&usb, data + at, (uint16_t)n);
    if (op == 1) tfw_usb_hid_out(&usb, data + at, (uint16_t)n);
    if (op == 2 && n >= 8) tfw_usb_setup(&usb, data + at, data + at + 8, (uint16_t)(n - 8));
    if (op == 3) tfw_usb_tick(&usb);
    at += n;
    const int16_t* out = tfw_device_outputs(&dev);
    for (int i = 0; i < 16; ++i) {
      require(out[i] >= config.deflection_min && out[i] <= config.deflection_max);
    }
  }
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  check_decoder(data, size);
  check_device(data, size);
  check_usb(data, size);
  return 0;
}
