#pragma once
// The USB bandwidth budget of docs/protocol.md as code: how many frames per second each link
// can carry for a given array, from the USB 2.0 transaction limits (no other traffic on the
// bus). `tactile bench stream` compares measured rates against it.

#include <cstddef>
#include <string>
#include <vector>

namespace tactile::display {

struct UsbLinkBudget {
  std::string name;              // e.g. "full-speed bulk"
  double packets_per_s = 0;      // most transactions per second on one endpoint
  std::size_t packet_bytes = 0;  // wire bytes per transaction
  // Frame bytes one transaction carries: the whole packet for bulk, 61 for a HID chunk.
  std::size_t frame_bytes_per_packet = 0;
  bool bulk = false;  // a bulk transfer ends with a short packet (zero-length if need be)
};

// Full- and high-speed, bulk and HID (64-byte interrupt reports every (micro)frame).
std::vector<UsbLinkBudget> usb_link_budgets();

// Transactions one frame of `contactors` needs on `link`.
std::size_t usb_packets_per_frame(const UsbLinkBudget& link, std::size_t contactors);

// Highest frame rate `link` carries for `contactors` (theoretical, bus to itself).
double usb_max_frame_rate_hz(const UsbLinkBudget& link, std::size_t contactors);

}  // namespace tactile::display
