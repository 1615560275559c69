#ifndef TACTILE_FW_DEVICE_H
#define TACTILE_FW_DEVICE_H
/*
 * The device core: receives frames into a FIFO and plays them at the device's own rate, with
 * the safety rules the host cannot bypass:
 *   - clamp: every output stays within [deflection_min, deflection_max];
 *   - slew limit: no output moves more than max_slew_per_tick between two ticks;
 *   - watchdog: when no frame has been played for watchdog_timeout_ms, every contactor ramps
 *     (at the slew limit) back to neutral (0);
 *   - malformed frames are counted by reason and dropped, never played.
 *
 * All state lives in tfw_device (no heap, no globals); the hardware is reached only through
 * the optional tfw_hw callback so the same code runs on the host (emulated device) and on a
 * Cortex-M4.
 *
 * Timing: tfw_device_tick() is called by the device's timer at rate_hz. The watchdog counts
 * from the last frame *played*, not received: frames already accepted are valid commands
 * within the limits, and a stalled host empties the FIFO within FIFO-depth ticks anyway.
 */
#include <stddef.h>
#include <stdint.h>

#include "tactile_fw/fifo.h"
#include "tactile_fw/wire.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TFW_FIRMWARE_VERSION "0.1.0"

typedef struct {
  uint16_t rows;
  uint16_t cols;
  /* Geometry, reported to the host in device information. Nanometres because pitches such
   * as the Latero's 1.6125 mm are not whole micrometres. */
  uint32_t pitch_x_nm;
  uint32_t pitch_y_nm;
  uint32_t contactor_width_nm;
  uint32_t contactor_height_nm;
  uint8_t axis;           /* deflection direction: 0 = x (along a row), 1 = y */
  int16_t deflection_min; /* wire units (0.1 um) */
  int16_t deflection_max;
  uint32_t max_slew_per_s; /* wire units per second; per tick = max_slew_per_s / rate_hz */
  uint16_t rate_hz;        /* playout rate, 1..max_rate_hz */
  uint16_t max_rate_hz;
  uint16_t watchdog_timeout_ms;
} tfw_config;

typedef enum {
  TFW_STATE_STOPPED = 0,   /* frames refused; outputs ramp to neutral */
  TFW_STATE_IDLE = 1,      /* started, no stream playing (before the first frame or after the
                              end of a stream or a watchdog trip): an empty FIFO is no underrun */
  TFW_STATE_STREAMING = 2, /* playing; a tick with an empty FIFO is an underrun */
} tfw_state;

typedef enum {
  TFW_CONFIG_OK = 0,
  TFW_CONFIG_BAD_SIZE = 1,  /* rows or cols 0, rows * cols > TFW_MAX_CONTACTORS, a zero
                               pitch or contactor size, or an axis other than 0 or 1 */
  TFW_CONFIG_BAD_RANGE = 2, /* deflection_min > 0 or deflection_max < 0 or min >= max */
  TFW_CONFIG_BAD_SLEW = 3,  /* slew limit below one unit per tick */
  TFW_CONFIG_BAD_RATE = 4,  /* rate 0 or above max_rate_hz */
  TFW_CONFIG_BAD_WATCHDOG = 5
} tfw_config_result;

/* Counters since the last tfw_device_start() (cumulative over a stream). */
typedef struct {
  uint32_t frames_received; /* accepted into the FIFO */
  uint32_t frames_played;
  uint32_t rejected[TFW_RESULT_COUNT]; /* frames refused, by tfw_result */
  uint32_t malformed_total;            /* rejected for a malformation (length..sequence) */
  uint32_t overflows;                  /* well-formed frames refused because the FIFO was full */
  uint32_t underruns;                  /* ticks with an empty FIFO while streaming */
  uint32_t sequence_gaps;              /* accepted frames whose sequence skipped numbers */
  uint32_t clamped_samples;            /* contactor values cut to the deflection range */
  uint32_t slew_limited_samples;       /* output steps cut to the slew limit */
  uint32_t watchdog_trips;
  uint32_t ticks;
  uint32_t last_sequence_played;
  uint16_t fifo_fill;
  uint16_t fifo_capacity;
  uint8_t state; /* tfw_state */
} tfw_status;

/* Hardware interface: called once per tick with the new outputs (may be NULL on the host). */
typedef struct {
  void (*write_outputs)(void* context, const int16_t* deflection, uint16_t count);
  void* context;
} tfw_hw;

typedef struct {
  tfw_config config;
  /* The limits given at init are the hardware's: the host may narrow them, never widen. */
  int16_t hard_deflection_min;
  int16_t hard_deflection_max;
  uint32_t hard_max_slew_per_s;
  tfw_hw hw;
  int16_t slew_per_tick;
  uint32_t watchdog_ticks;
  uint32_t ticks_since_frame; /* saturates at watchdog_ticks */
  uint8_t state;
  uint8_t have_sequence;
  uint32_t last_sequence;
  tfw_status counters;
  int16_t target[TFW_MAX_CONTACTORS];
  int16_t output[TFW_MAX_CONTACTORS];
  tfw_fifo fifo;
} tfw_device;

tfw_config_result tfw_config_check(const tfw_config* config);
const char* tfw_config_result_name(tfw_config_result result);

/* Initialises a stopped device with all outputs at neutral. `hw` may be NULL. */
tfw_config_result tfw_device_init(tfw_device* dev, const tfw_config* config, const tfw_hw* hw);

/* Starts a stream at `rate_hz` (0 keeps the configured rate): resets the counters and the
 * sequence tracking, empties the FIFO. Fails with TFW_CONFIG_BAD_RATE above max_rate_hz. */
tfw_config_result tfw_device_start(tfw_device* dev, uint16_t rate_hz);

/* Narrows the clamp range and slew limit (the "set limits" request). Limits outside the ones
 * given at init, an empty range or a range that excludes neutral are refused
 * (TFW_CONFIG_BAD_RANGE, TFW_CONFIG_BAD_SLEW) and leave the device unchanged. */
tfw_config_result tfw_device_set_limits(tfw_device* dev, int16_t deflection_min,
                                        int16_t deflection_max, uint32_t max_slew_per_s);

/* Stops: drops queued frames and ramps every output to neutral at the slew limit. */
void tfw_device_stop(tfw_device* dev);

/* Accepts one encoded frame from the host. Returns TFW_OK when queued; otherwise the frame is
 * counted by reason and dropped. TFW_ERR_FIFO_FULL means the host must wait and resend (the
 * USB glue avoids it by not arming the OUT endpoint while tfw_device_can_receive() is 0). */
tfw_result tfw_device_receive(tfw_device* dev, const uint8_t* bytes, size_t len);
int tfw_device_can_receive(const tfw_device* dev);

/* One playout period: plays the next frame or holds (counting an underrun while streaming),
 * runs the watchdog, then applies clamp and slew limit and writes the outputs. */
void tfw_device_tick(tfw_device* dev);

const int16_t* tfw_device_outputs(const tfw_device* dev);
uint16_t tfw_device_contactor_count(const tfw_device* dev);
void tfw_device_status(const tfw_device* dev, tfw_status* status);

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_DEVICE_H */
