// The bandwidth budget against the arithmetic written out in docs/protocol.md.
#include <gtest/gtest.h>

#include "tactile/display/usb_budget.hpp"

namespace tactile::display {
namespace {

UsbLinkBudget link(const std::string& name) {
  for (const auto& l : usb_link_budgets()) {
    if (l.name == name) return l;
  }
  ADD_FAILURE() << "no link " << name;
  return {};
}

TEST(UsbBudget, StressArrayOnEachLink) {
  // 10 x 10: 16 + 200 = 216 bytes.
  EXPECT_EQ(usb_packets_per_frame(link("full-speed bulk"), 100), 4u);  // 64+64+64+24
  EXPECT_NEAR(usb_max_frame_rate_hz(link("full-speed bulk"), 100), 19000.0 / 4, 1e-9);
  EXPECT_EQ(usb_packets_per_frame(link("high-speed bulk"), 100), 1u);
  EXPECT_NEAR(usb_max_frame_rate_hz(link("high-speed bulk"), 100), 104000.0, 1e-9);
  EXPECT_EQ(usb_packets_per_frame(link("full-speed HID"), 100), 4u);  // 61+61+61+33
  EXPECT_NEAR(usb_max_frame_rate_hz(link("full-speed HID"), 100), 250.0, 1e-9);
  EXPECT_NEAR(usb_max_frame_rate_hz(link("high-speed HID"), 100), 2000.0, 1e-9);
}

TEST(UsbBudget, ExactMultipleNeedsAZeroLengthPacket) {
  // 24 contactors: 16 + 48 = 64 bytes, one full packet plus the zero-length one.
  EXPECT_EQ(usb_packets_per_frame(link("full-speed bulk"), 24), 2u);
  // 248 contactors: 512 bytes at high speed, likewise.
  EXPECT_EQ(usb_packets_per_frame(link("high-speed bulk"), 248), 2u);
  EXPECT_EQ(usb_packets_per_frame(link("full-speed HID"), 24), 2u);  // 61 + 3
}

TEST(UsbBudget, LargestArray) {
  // 16 x 16: 528 bytes = 8 x 64 + 16 (FS bulk), 512 + 16 (HS bulk), 9 HID chunks.
  EXPECT_EQ(usb_packets_per_frame(link("full-speed bulk"), 256), 9u);
  EXPECT_EQ(usb_packets_per_frame(link("high-speed bulk"), 256), 2u);
  EXPECT_EQ(usb_packets_per_frame(link("high-speed HID"), 256), 9u);
}

}  // namespace
}  // namespace tactile::display
