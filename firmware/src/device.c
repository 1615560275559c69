/* Device core: FIFO playout with clamp, slew limit and watchdog; see tactile_fw/device.h. */
#include "tactile_fw/device.h"

#include <stddef.h>
#include <string.h>

tfw_config_result tfw_config_check(const tfw_config* config) {
  const uint32_t count = (uint32_t)config->rows * (uint32_t)config->cols;
  if (config->rows == 0 || config->cols == 0 || count > TFW_MAX_CONTACTORS) {
    return TFW_CONFIG_BAD_SIZE;
  }
  if (config->pitch_x_nm == 0 || config->pitch_y_nm == 0 || config->contactor_width_nm == 0 ||
      config->contactor_height_nm == 0 || config->axis > 1) {
    return TFW_CONFIG_BAD_SIZE;
  }
  if (config->deflection_min > 0 || config->deflection_max < 0 ||
      config->deflection_min >= config->deflection_max) {
    return TFW_CONFIG_BAD_RANGE;
  }
  if (config->max_rate_hz == 0 || config->rate_hz == 0 || config->rate_hz > config->max_rate_hz) {
    return TFW_CONFIG_BAD_RATE;
  }
  /* Checked against the highest rate so that any allowed rate gives at least one unit per
   * tick; a zero slew would freeze the outputs and defeat the watchdog. */
  if (config->max_slew_per_s < config->max_rate_hz) return TFW_CONFIG_BAD_SLEW;
  if (config->watchdog_timeout_ms == 0) return TFW_CONFIG_BAD_WATCHDOG;
  return TFW_CONFIG_OK;
}

const char* tfw_config_result_name(tfw_config_result result) {
  switch (result) {
    case TFW_CONFIG_OK:
      return "ok";
    case TFW_CONFIG_BAD_SIZE:
      return "bad_size";
    case TFW_CONFIG_BAD_RANGE:
      return "bad_range";
    case TFW_CONFIG_BAD_SLEW:
      return "bad_slew";
    case TFW_CONFIG_BAD_RATE:
      return "bad_rate";
    case TFW_CONFIG_BAD_WATCHDOG:
      return "bad_watchdog";
  }
  return "unknown";
}

/* Derived per-tick quantities; recomputed whenever the rate changes. */
static void apply_rate(tfw_device* dev, uint16_t rate_hz) {
  dev->config.rate_hz = rate_hz;
  const uint32_t per_tick = dev->config.max_slew_per_s / rate_hz;
  dev->slew_per_tick = (int16_t)(per_tick > 32767u ? 32767u : per_tick);
  /* Round up so the device never gives up on the host earlier than promised. */
  dev->watchdog_ticks = ((uint32_t)dev->config.watchdog_timeout_ms * rate_hz + 999u) / 1000u;
  if (dev->watchdog_ticks == 0) dev->watchdog_ticks = 1;
}

static void reset_counters(tfw_device* dev) {
  memset(&dev->counters, 0, sizeof dev->counters);
}

tfw_config_result tfw_device_init(tfw_device* dev, const tfw_config* config, const tfw_hw* hw) {
  const tfw_config_result check = tfw_config_check(config);
  if (check != TFW_CONFIG_OK) return check;
  dev->config = *config;
  dev->hard_deflection_min = config->deflection_min;
  dev->hard_deflection_max = config->deflection_max;
  dev->hard_max_slew_per_s = config->max_slew_per_s;
  if (hw != NULL) {
    dev->hw = *hw;
  } else {
    dev->hw.write_outputs = NULL;
    dev->hw.context = NULL;
  }
  apply_rate(dev, config->rate_hz);
  dev->ticks_since_frame = dev->watchdog_ticks;
  dev->state = TFW_STATE_STOPPED;
  dev->have_sequence = 0;
  dev->last_sequence = 0;
  reset_counters(dev);
  memset(dev->target, 0, sizeof dev->target);
  memset(dev->output, 0, sizeof dev->output);
  tfw_fifo_init(&dev->fifo);
  return TFW_CONFIG_OK;
}

tfw_config_result tfw_device_start(tfw_device* dev, uint16_t rate_hz) {
  if (rate_hz != 0) {
    if (rate_hz > dev->config.max_rate_hz) return TFW_CONFIG_BAD_RATE;
    apply_rate(dev, rate_hz);
  }
  tfw_fifo_clear(&dev->fifo);
  reset_counters(dev);
  dev->have_sequence = 0;
  dev->state = TFW_STATE_IDLE;
  return TFW_CONFIG_OK;
}

tfw_config_result tfw_device_set_limits(tfw_device* dev, int16_t deflection_min,
                                        int16_t deflection_max, uint32_t max_slew_per_s) {
  if (deflection_min < dev->hard_deflection_min || deflection_max > dev->hard_deflection_max ||
      deflection_min > 0 || deflection_max < 0 || deflection_min >= deflection_max) {
    return TFW_CONFIG_BAD_RANGE;
  }
  /* Same floor as tfw_config_check: at least one unit per tick at the highest rate. */
  if (max_slew_per_s > dev->hard_max_slew_per_s || max_slew_per_s < dev->config.max_rate_hz) {
    return TFW_CONFIG_BAD_SLEW;
  }
  dev->config.deflection_min = deflection_min;
  dev->config.deflection_max = deflection_max;
  dev->config.max_slew_per_s = max_slew_per_s;
  apply_rate(dev, dev->config.rate_hz);
  return TFW_CONFIG_OK;
}

void tfw_device_stop(tfw_device* dev) {
  tfw_fifo_clear(&dev->fifo);
  memset(dev->target, 0, sizeof dev->target);
  dev->state = TFW_STATE_STOPPED;
}

uint16_t tfw_device_contactor_count(const tfw_device* dev) {
  return (uint16_t)(dev->config.rows * dev->config.cols);
}

int tfw_device_can_receive(const tfw_device* dev) {
  return dev->state != TFW_STATE_STOPPED && !tfw_fifo_full(&dev->fifo);
}

static tfw_result reject(tfw_device* dev, tfw_result why) {
  dev->counters.rejected[why]++;
  if (why == TFW_ERR_FIFO_FULL) {
    dev->counters.overflows++;
  } else if (why != TFW_ERR_NOT_STARTED) {
    dev->counters.malformed_total++;
  }
  return why;
}

tfw_result tfw_device_receive(tfw_device* dev, const uint8_t* bytes, size_t len) {
  if (dev->state == TFW_STATE_STOPPED) return reject(dev, TFW_ERR_NOT_STARTED);
  tfw_frame_header header;
  tfw_frame* slot = tfw_fifo_reserve(&dev->fifo);
  /* Decode straight into the FIFO slot; it only becomes visible on commit. With a full FIFO
   * the frame is still verified so that a malformed frame is reported as malformed. */
  const tfw_result decoded =
      tfw_decode_frame(bytes, len, &header, slot ? slot->deflection : NULL, TFW_MAX_CONTACTORS);
  if (decoded != TFW_OK) return reject(dev, decoded);
  if (header.contactor_count != tfw_device_contactor_count(dev)) {
    return reject(dev, TFW_ERR_BAD_COUNT);
  }
  if (dev->have_sequence && !tfw_sequence_is_newer(header.sequence, dev->last_sequence)) {
    return reject(dev, TFW_ERR_BAD_SEQUENCE);
  }
  /* Checked last so that the host can resend this very frame once there is room. */
  if (slot == NULL) return reject(dev, TFW_ERR_FIFO_FULL);
  if (dev->have_sequence && header.sequence != dev->last_sequence + 1u) {
    dev->counters.sequence_gaps++;
  }
  dev->have_sequence = 1;
  dev->last_sequence = header.sequence;
  slot->sequence = header.sequence;
  slot->flags = header.flags;
  slot->contactor_count = header.contactor_count;
  tfw_fifo_commit(&dev->fifo);
  dev->counters.frames_received++;
  return TFW_OK;
}

static int16_t clamp_value(const tfw_device* dev, int16_t v, uint32_t* clamped) {
  if (v < dev->config.deflection_min) {
    (*clamped)++;
    return dev->config.deflection_min;
  }
  if (v > dev->config.deflection_max) {
    (*clamped)++;
    return dev->config.deflection_max;
  }
  return v;
}

/* Takes the next frame as the new target, or handles starvation and the watchdog. */
static void update_target(tfw_device* dev) {
  const uint16_t n = tfw_device_contactor_count(dev);
  const tfw_frame* frame = dev->state == TFW_STATE_STOPPED ? NULL : tfw_fifo_front(&dev->fifo);
  if (frame != NULL) {
    for (uint16_t i = 0; i < n; ++i) {
      dev->target[i] = clamp_value(dev, frame->deflection[i], &dev->counters.clamped_samples);
    }
    dev->counters.frames_played++;
    dev->counters.last_sequence_played = frame->sequence;
    dev->state = (frame->flags & TFW_FLAG_END_OF_STREAM) ? TFW_STATE_IDLE : TFW_STATE_STREAMING;
    tfw_fifo_pop(&dev->fifo);
    dev->ticks_since_frame = 0;
    return;
  }
  if (dev->state == TFW_STATE_STREAMING) dev->counters.underruns++;
  if (dev->ticks_since_frame < dev->watchdog_ticks) {
    dev->ticks_since_frame++;
    if (dev->ticks_since_frame == dev->watchdog_ticks) {
      /* Frames stopped arriving: the stream is over, whatever the host believes. */
      /* Only a stream that did not end properly counts as a trip; after an end-of-stream
       * frame the ramp to neutral is the normal way to finish. */
      if (dev->state == TFW_STATE_STREAMING) {
        dev->counters.watchdog_trips++;
        dev->state = TFW_STATE_IDLE;
      }
      memset(dev->target, 0, sizeof dev->target);
    }
  }
}

void tfw_device_tick(tfw_device* dev) {
  dev->counters.ticks++;
  update_target(dev);
  const uint16_t n = tfw_device_contactor_count(dev);
  const int32_t step = dev->slew_per_tick;
  for (uint16_t i = 0; i < n; ++i) {
    int32_t delta = (int32_t)dev->target[i] - (int32_t)dev->output[i];
    if (delta > step) {
      delta = step;
      dev->counters.slew_limited_samples++;
    } else if (delta < -step) {
      delta = -step;
      dev->counters.slew_limited_samples++;
    }
    dev->output[i] = (int16_t)(dev->output[i] + delta);
  }
  if (dev->hw.write_outputs != NULL) dev->hw.write_outputs(dev->hw.context, dev->output, n);
}

const int16_t* tfw_device_outputs(const tfw_device* dev) {
  return dev->output;
}

void tfw_device_status(const tfw_device* dev, tfw_status* status) {
  *status = dev->counters;
  status->fifo_fill = tfw_fifo_count(&dev->fifo);
  status->fifo_capacity = tfw_fifo_capacity(&dev->fifo);
  status->state = dev->state;
}
