#ifndef TACTILE_FW_CONTROL_H
#define TACTILE_FW_CONTROL_H
/*
 * Replies to the control requests "device information" and "status", as fixed-size
 * little-endian byte blocks shared by the firmware (encode) and the host (decode). The USB
 * request codes and descriptors around them are defined with the USB glue (usb.h); the
 * emulated device already answers through these encodings so that the host code paths are
 * the same for both.
 *
 * Device information, TFW_INFO_BYTES = 48:
 *   0 u8 protocol version   1 u8 axis (0 x, 1 y)   2 u16 rows   4 u16 cols
 *   6 i16 deflection_min (0.1 um)   8 i16 deflection_max   10 u16 max_rate_hz
 *   12 u32 pitch_x_nm   16 u32 pitch_y_nm   20 u32 contactor_width_nm
 *   24 u32 contactor_height_nm   28 u32 max_slew_per_s (0.1 um/s)
 *   32 u16 watchdog_timeout_ms   34 u16 fifo_capacity (frames)
 *   36 char[12] firmware version, NUL-padded
 *
 * Status, TFW_STATUS_BYTES = 96:
 *   0 u8 state   1 u8 reserved (0)   2 u16 fifo_fill   4 u16 fifo_capacity   6 u16 rate_hz
 *   8 u32 frames_received   12 frames_played   16 malformed_total   20 overflows
 *   24 underruns   28 sequence_gaps   32 clamped_samples   36 slew_limited_samples
 *   40 watchdog_trips   44 ticks   48 last_sequence_played
 *   52 u32 rejected[TFW_RESULT_COUNT] (by tfw_result code)   92 u32 reserved (0)
 *
 * Fill report, TFW_FILL_BYTES = 16 (sent unasked on the status IN endpoints so that the host
 * can pace itself without a control request per frame):
 *   0 u8 state   1 u8 reserved (0)   2 u16 fifo_fill   4 u16 fifo_capacity   6 u16 rate_hz
 *   8 u32 frames_played   12 u32 underruns
 */
#include <stddef.h>
#include <stdint.h>

#include "tactile_fw/device.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TFW_INFO_BYTES 48u
#define TFW_STATUS_BYTES 96u
#define TFW_VERSION_CHARS 12u
#define TFW_FILL_BYTES 16u

typedef struct {
  uint8_t protocol_version;
  tfw_config config; /* rate_hz holds the current playout rate */
  uint16_t fifo_capacity;
  char firmware_version[TFW_VERSION_CHARS + 1]; /* always NUL-terminated */
} tfw_device_info;

typedef struct {
  tfw_status status;
  uint16_t rate_hz;
} tfw_status_report;

typedef struct {
  uint8_t state; /* tfw_state */
  uint16_t fifo_fill;
  uint16_t fifo_capacity;
  uint16_t rate_hz;
  uint32_t frames_played;
  uint32_t underruns;
} tfw_fill_report;

/* Encoders return the number of bytes written, or 0 when `capacity` is too small. */
size_t tfw_encode_info(const tfw_device* dev, uint8_t* out, size_t capacity);
size_t tfw_encode_status(const tfw_device* dev, uint8_t* out, size_t capacity);
size_t tfw_encode_fill(const tfw_device* dev, uint8_t* out, size_t capacity);

/* Decoders check the length (TFW_ERR_BAD_LENGTH) and, for information, the protocol version
 * (TFW_ERR_BAD_VERSION). */
tfw_result tfw_decode_info(const uint8_t* bytes, size_t len, tfw_device_info* info);
tfw_result tfw_decode_status(const uint8_t* bytes, size_t len, tfw_status_report* report);
tfw_result tfw_decode_fill(const uint8_t* bytes, size_t len, tfw_fill_report* report);

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_CONTROL_H */
