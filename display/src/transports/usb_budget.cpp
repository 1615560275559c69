#include "tactile/display/usb_budget.hpp"

#include "tactile_fw/usb.h"
#include "tactile_fw/wire.h"

namespace tactile::display {

std::vector<UsbLinkBudget> usb_link_budgets() {
  // USB 2.0 table 5-10 and 5-8: per 1 ms frame at most 19 full-speed bulk transactions of 64
  // bytes; per 125 us microframe at most 13 high-speed bulk transactions of 512 bytes. A HID
  // interrupt endpoint with bInterval 1 gets one transaction per (micro)frame.
  return {
      {"full-speed bulk", 19.0 * 1000.0, TFW_USB_BULK_PACKET_FS, TFW_USB_BULK_PACKET_FS, true},
      {"high-speed bulk", 13.0 * 8000.0, TFW_USB_BULK_PACKET_HS, TFW_USB_BULK_PACKET_HS, true},
      {"full-speed HID", 1000.0, TFW_USB_HID_PACKET, TFW_HID_CHUNK_PAYLOAD, false},
      {"high-speed HID", 8000.0, TFW_USB_HID_PACKET, TFW_HID_CHUNK_PAYLOAD, false},
  };
}

std::size_t usb_packets_per_frame(const UsbLinkBudget& link, std::size_t contactors) {
  const std::size_t bytes = TFW_FRAME_BYTES(contactors);
  const std::size_t per = link.frame_bytes_per_packet;
  // Bulk: full packets then the short one that ends the transfer (zero-length when the frame
  // is an exact multiple). HID: chunks, the last one padded.
  return link.bulk ? bytes / per + 1 : (bytes + per - 1) / per;
}

double usb_max_frame_rate_hz(const UsbLinkBudget& link, std::size_t contactors) {
  return link.packets_per_s / static_cast<double>(usb_packets_per_frame(link, contactors));
}

}  // namespace tactile::display
