/* Device information and status replies; see tactile_fw/control.h. */
#include "tactile_fw/control.h"

#include "le_bytes.h"

#include <string.h>

size_t tfw_encode_info(const tfw_device* dev, uint8_t* out, size_t capacity) {
  if (capacity < TFW_INFO_BYTES) return 0;
  const tfw_config* c = &dev->config;
  memset(out, 0, TFW_INFO_BYTES);
  out[0] = (uint8_t)TFW_PROTOCOL_VERSION;
  out[1] = c->axis;
  tfw_put_u16(out + 2, c->rows);
  tfw_put_u16(out + 4, c->cols);
  tfw_put_u16(out + 6, (uint16_t)c->deflection_min);
  tfw_put_u16(out + 8, (uint16_t)c->deflection_max);
  tfw_put_u16(out + 10, c->max_rate_hz);
  tfw_put_u32(out + 12, c->pitch_x_nm);
  tfw_put_u32(out + 16, c->pitch_y_nm);
  tfw_put_u32(out + 20, c->contactor_width_nm);
  tfw_put_u32(out + 24, c->contactor_height_nm);
  tfw_put_u32(out + 28, c->max_slew_per_s);
  tfw_put_u16(out + 32, c->watchdog_timeout_ms);
  tfw_put_u16(out + 34, (uint16_t)TFW_FIFO_CAPACITY);
  const char* version = TFW_FIRMWARE_VERSION;
  for (size_t i = 0; i < TFW_VERSION_CHARS && version[i] != '\0'; ++i) {
    out[36 + i] = (uint8_t)version[i];
  }
  return TFW_INFO_BYTES;
}

/* The status reply and the fill report begin with the same 8 bytes (state, FIFO fill and
 * capacity, rate), written here for both so that they cannot come apart. `s` receives the status
 * they were taken from, for the rest of the reply. */
static void put_report_head(const tfw_device* dev, uint8_t* out, size_t bytes, tfw_status* s) {
  tfw_device_status(dev, s);
  memset(out, 0, bytes);
  out[0] = s->state;
  tfw_put_u16(out + 2, s->fifo_fill);
  tfw_put_u16(out + 4, s->fifo_capacity);
  tfw_put_u16(out + 6, dev->config.rate_hz);
}

/* Reads the 8 bytes put_report_head writes, for the status reply and the fill report alike. */
static void get_report_head(const uint8_t* bytes, uint8_t* state, uint16_t* fifo_fill,
                            uint16_t* fifo_capacity, uint16_t* rate_hz) {
  *state = bytes[0];
  *fifo_fill = tfw_get_u16(bytes + 2);
  *fifo_capacity = tfw_get_u16(bytes + 4);
  *rate_hz = tfw_get_u16(bytes + 6);
}

size_t tfw_encode_status(const tfw_device* dev, uint8_t* out, size_t capacity) {
  if (capacity < TFW_STATUS_BYTES) return 0;
  tfw_status s;
  put_report_head(dev, out, TFW_STATUS_BYTES, &s);
  const uint32_t counters[] = {
      s.frames_received, s.frames_played, s.malformed_total,     s.overflows,
      s.underruns,       s.sequence_gaps, s.clamped_samples,     s.slew_limited_samples,
      s.watchdog_trips,  s.ticks,         s.last_sequence_played};
  for (size_t i = 0; i < sizeof counters / sizeof counters[0]; ++i) {
    tfw_put_u32(out + 8 + 4 * i, counters[i]);
  }
  for (size_t r = 0; r < TFW_RESULT_COUNT; ++r) tfw_put_u32(out + 52 + 4 * r, s.rejected[r]);
  return TFW_STATUS_BYTES;
}

tfw_result tfw_decode_info(const uint8_t* bytes, size_t len, tfw_device_info* info) {
  if (len != TFW_INFO_BYTES) return TFW_ERR_BAD_LENGTH;
  if (bytes[0] != TFW_PROTOCOL_VERSION) return TFW_ERR_BAD_VERSION;
  memset(info, 0, sizeof *info);
  info->protocol_version = bytes[0];
  tfw_config* c = &info->config;
  c->axis = bytes[1];
  c->rows = tfw_get_u16(bytes + 2);
  c->cols = tfw_get_u16(bytes + 4);
  c->deflection_min = tfw_get_i16(bytes + 6);
  c->deflection_max = tfw_get_i16(bytes + 8);
  c->max_rate_hz = tfw_get_u16(bytes + 10);
  c->rate_hz = c->max_rate_hz;
  c->pitch_x_nm = tfw_get_u32(bytes + 12);
  c->pitch_y_nm = tfw_get_u32(bytes + 16);
  c->contactor_width_nm = tfw_get_u32(bytes + 20);
  c->contactor_height_nm = tfw_get_u32(bytes + 24);
  c->max_slew_per_s = tfw_get_u32(bytes + 28);
  c->watchdog_timeout_ms = tfw_get_u16(bytes + 32);
  info->fifo_capacity = tfw_get_u16(bytes + 34);
  for (size_t i = 0; i < TFW_VERSION_CHARS; ++i) {
    info->firmware_version[i] = (char)bytes[36 + i];
  }
  info->firmware_version[TFW_VERSION_CHARS] = '\0';
  return TFW_OK;
}

tfw_result tfw_decode_status(const uint8_t* bytes, size_t len, tfw_status_report* report) {
  if (len != TFW_STATUS_BYTES) return TFW_ERR_BAD_LENGTH;
  memset(report, 0, sizeof *report);
  tfw_status* s = &report->status;
  get_report_head(bytes, &s->state, &s->fifo_fill, &s->fifo_capacity, &report->rate_hz);
  uint32_t* counters[] = {
      &s->frames_received, &s->frames_played, &s->malformed_total,     &s->overflows,
      &s->underruns,       &s->sequence_gaps, &s->clamped_samples,     &s->slew_limited_samples,
      &s->watchdog_trips,  &s->ticks,         &s->last_sequence_played};
  for (size_t i = 0; i < sizeof counters / sizeof counters[0]; ++i) {
    *counters[i] = tfw_get_u32(bytes + 8 + 4 * i);
  }
  for (size_t r = 0; r < TFW_RESULT_COUNT; ++r) s->rejected[r] = tfw_get_u32(bytes + 52 + 4 * r);
  return TFW_OK;
}

size_t tfw_encode_fill(const tfw_device* dev, uint8_t* out, size_t capacity) {
  if (capacity < TFW_FILL_BYTES) return 0;
  tfw_status s;
  put_report_head(dev, out, TFW_FILL_BYTES, &s);
  tfw_put_u32(out + 8, s.frames_played);
  tfw_put_u32(out + 12, s.underruns);
  return TFW_FILL_BYTES;
}

tfw_result tfw_decode_fill(const uint8_t* bytes, size_t len, tfw_fill_report* report) {
  if (len != TFW_FILL_BYTES) return TFW_ERR_BAD_LENGTH;
  get_report_head(bytes, &report->state, &report->fifo_fill, &report->fifo_capacity,
                  &report->rate_hz);
  report->frames_played = tfw_get_u32(bytes + 8);
  report->underruns = tfw_get_u32(bytes + 12);
  return TFW_OK;
}
