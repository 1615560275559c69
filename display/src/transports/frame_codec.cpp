// Conversion between micrometres and the firmware's wire frames.
#include "tactile/display/frame_codec.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tactile_fw/wire.h"

namespace tactile::display {

std::int16_t to_wire_units(float deflection_um) {
  const double units = std::round(static_cast<double>(deflection_um) * TFW_UNITS_PER_UM);
  if (std::isnan(units)) return 0;  // never reached for validated movies; neutral is safe
  if (units > 32767.0) return 32767;
  if (units < -32768.0) return -32768;
  return static_cast<std::int16_t>(units);
}

float from_wire_units(std::int16_t units) {
  return static_cast<float>(units) / static_cast<float>(TFW_UNITS_PER_UM);
}

std::vector<std::uint8_t> encode_frame(std::span<const float> deflection_um, std::uint32_t sequence,
                                       bool end_of_stream) {
  if (deflection_um.empty() || deflection_um.size() > TFW_MAX_CONTACTORS) {
    throw std::invalid_argument("frame has " + std::to_string(deflection_um.size()) +
                                " contactors; the protocol carries 1.." +
                                std::to_string(TFW_MAX_CONTACTORS));
  }
  std::vector<std::int16_t> units(deflection_um.size());
  for (std::size_t i = 0; i < units.size(); ++i) units[i] = to_wire_units(deflection_um[i]);
  std::vector<std::uint8_t> bytes(TFW_FRAME_BYTES(units.size()));
  std::size_t len = 0;
  const tfw_result r =
      tfw_encode_frame(sequence, end_of_stream ? TFW_FLAG_END_OF_STREAM : 0, units.data(),
                       static_cast<std::uint16_t>(units.size()), bytes.data(), bytes.size(), &len);
  if (r != TFW_OK) {
    throw std::logic_error(std::string("frame encoding failed: ") + tfw_result_name(r));
  }
  bytes.resize(len);
  return bytes;
}

}  // namespace tactile::display
