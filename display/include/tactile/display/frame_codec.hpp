#pragma once
// Host side of the device wire format (firmware/include/tactile_fw/wire.h): micrometres to
// wire units and whole frames to bytes.

#include <cstdint>
#include <span>
#include <vector>

namespace tactile::display {

// Wire units are 0.1 um; values round to the nearest unit and saturate at the i16 limits
// (+-3276.7 um), so an absurd value becomes a large one that the device then clamps.
std::int16_t to_wire_units(float deflection_um);
float from_wire_units(std::int16_t units);

// Encodes one frame (row-major contactor order). Throws std::invalid_argument for an empty
// frame or more contactors than the protocol carries (TFW_MAX_CONTACTORS).
std::vector<std::uint8_t> encode_frame(std::span<const float> deflection_um, std::uint32_t sequence,
                                       bool end_of_stream = false);

}  // namespace tactile::display
