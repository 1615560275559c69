#pragma once
// Host side of the control requests and replies (firmware/include/tactile_fw/control.h): device
// information and status blocks to DeviceInfo / DeviceStatus, and the start request's rate.
// Every transport decodes the device's bytes through these, the emulated one included.

#include <cstdint>
#include <span>
#include <string>

#include "tactile/display/transport.hpp"

namespace tactile::display {

// `layout_name` and the identity strings come from elsewhere (USB string descriptors, or the
// emulator's options). Throws TransportError naming the problem for a reply of the wrong
// length or protocol version.
DeviceInfo decode_device_info(std::span<const std::uint8_t> reply, Backend backend,
                              const std::string& name, const std::string& serial,
                              const std::string& layout_name);

DeviceStatus decode_device_status(std::span<const std::uint8_t> reply);

// The start request's value: the playout rate in whole Hz, rounded and held to 0..65535.
std::uint16_t start_rate_value(double rate_hz);

}  // namespace tactile::display
