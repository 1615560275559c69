// Decoding of device information and status replies; see control_codec.hpp.
#include "tactile/display/control_codec.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "tactile/display/frame_codec.hpp"
#include "tactile_fw/control.h"

namespace tactile::display {

std::string to_string(Backend backend) {
  return name_in(kBackendNames, backend);
}

Backend parse_backend(std::string_view name) {
  return parse_name("back end", name, kBackendNames);
}

DeviceInfo decode_device_info(std::span<const std::uint8_t> reply, Backend backend,
                              const std::string& name, const std::string& serial,
                              const std::string& layout_name) {
  tfw_device_info fw{};
  const tfw_result r = tfw_decode_info(reply.data(), reply.size(), &fw);
  if (r != TFW_OK) {
    throw TransportError(
        fmt::format("device '{}': device information reply of {} bytes is "
                    "invalid ({}; expected {} bytes, protocol {})",
                    name, reply.size(), tfw_result_name(r), TFW_INFO_BYTES, TFW_PROTOCOL_VERSION));
  }
  const tfw_config& c = fw.config;
  DeviceInfo d;
  d.backend = backend;
  d.name = name;
  d.serial = serial;
  d.firmware_version = fw.firmware_version;
  d.protocol_version = fw.protocol_version;
  d.layout.name = layout_name;
  d.layout.rows = c.rows;
  d.layout.cols = c.cols;
  d.layout.pitch_x_mm = c.pitch_x_nm / 1e6;
  d.layout.pitch_y_mm = c.pitch_y_nm / 1e6;
  d.layout.contactor_width_mm = c.contactor_width_nm / 1e6;
  d.layout.contactor_height_mm = c.contactor_height_nm / 1e6;
  d.layout.axis = c.axis == 0 ? movie::DeflectionAxis::x : movie::DeflectionAxis::y;
  d.layout.deflection_min_um = from_wire_units(c.deflection_min);
  d.layout.deflection_max_um = from_wire_units(c.deflection_max);
  d.layout.max_rate_hz = c.max_rate_hz;
  d.max_slew_um_per_s = static_cast<double>(c.max_slew_per_s) / TFW_UNITS_PER_UM;
  d.watchdog_timeout_s = c.watchdog_timeout_ms / 1000.0;
  d.fifo_capacity_frames = fw.fifo_capacity;
  return d;
}

DeviceStatus decode_device_status(std::span<const std::uint8_t> reply) {
  tfw_status_report fw{};
  const tfw_result r = tfw_decode_status(reply.data(), reply.size(), &fw);
  if (r != TFW_OK) {
    throw TransportError(fmt::format("device status reply of {} bytes is invalid ({}; expected {})",
                                     reply.size(), tfw_result_name(r), TFW_STATUS_BYTES));
  }
  const tfw_status& s = fw.status;
  DeviceStatus d;
  d.frames_received = s.frames_received;
  d.frames_played = s.frames_played;
  d.malformed = s.malformed_total;
  for (int k = 1; k < TFW_RESULT_COUNT; ++k) {
    if (s.rejected[k] != 0) {
      d.rejected_by_reason[tfw_result_name(static_cast<tfw_result>(k))] = s.rejected[k];
    }
  }
  d.overflows = s.overflows;
  d.underruns = s.underruns;
  d.sequence_gaps = s.sequence_gaps;
  d.clamped_samples = s.clamped_samples;
  d.slew_limited_samples = s.slew_limited_samples;
  d.watchdog_trips = s.watchdog_trips;
  d.ticks = s.ticks;
  d.last_sequence_played = s.last_sequence_played;
  d.fifo_fill = s.fifo_fill;
  d.fifo_capacity = s.fifo_capacity;
  d.started = s.state != TFW_STATE_STOPPED;
  d.streaming = s.state == TFW_STATE_STREAMING;
  d.rate_hz = fw.rate_hz;
  return d;
}

std::uint16_t start_rate_value(double rate_hz) {
  return static_cast<std::uint16_t>(std::clamp(rate_hz, 0.0, 65535.0) + 0.5);
}

}  // namespace tactile::display
