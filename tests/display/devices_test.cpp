// USB listing. Without a device attached (CI, containers) the real libusb and hidapi calls
// must come back empty rather than fail; tests/usb finds a fake device under umockdev.
#include <gtest/gtest.h>

#include "tactile/display/devices.hpp"

namespace tactile::display {
namespace {

TEST(Devices, ListingOnlyReportsTheProjectsVendorAndProduct) {
  const std::vector<DeviceDescription> devices = list_usb_devices();
  for (const DeviceDescription& d : devices) {
    EXPECT_EQ(d.vendor_id, kUsbVendorId);
    EXPECT_EQ(d.product_id, kUsbProductId);
    EXPECT_TRUE(d.backend == "libusb" || d.backend == "hidapi") << d.backend;
    EXPECT_FALSE(d.path.empty());
  }
  // Listing twice gives the same answer: enumeration holds no state between calls.
  EXPECT_EQ(list_usb_devices().size(), devices.size());
}

}  // namespace
}  // namespace tactile::display
