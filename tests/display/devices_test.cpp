// USB listing. Without a device attached (CI, containers) the real libusb and hidapi calls
// must come back empty rather than fail; tests/usb finds a fake device under umockdev.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "tactile/display/usb_transports.hpp"

namespace tactile::display {
namespace {

TEST(Devices, ListingOnlyReportsTheProjectsVendorAndProduct) {
  const std::vector<DeviceDescription> devices = list_usb_devices();
  for (const DeviceDescription& d : devices) {
    EXPECT_EQ(d.vendor_id, kUsbVendorId);
    EXPECT_EQ(d.product_id, kUsbProductId);
    EXPECT_TRUE(d.backend == Backend::libusb || d.backend == Backend::hidapi)
        << to_string(d.backend);
    EXPECT_FALSE(d.path.empty());
  }
  // Listing twice gives the same answer: enumeration holds no state between calls.
  EXPECT_EQ(list_usb_devices().size(), devices.size());
}

// Back-end names are printed by `tactile devices` and passed in by the VM harness: they must
// round-trip and keep their spelling.
TEST(Devices, BackendNamesRoundTrip) {
  for (const Backend b : kBackends) EXPECT_EQ(parse_backend(to_string(b)), b);
  EXPECT_EQ(to_string(Backend::libusb), "libusb");
  EXPECT_EQ(to_string(Backend::hidapi), "hidapi");
  EXPECT_EQ(to_string(Backend::emulated), "emulated");
  EXPECT_EQ(to_string(Backend::latero), "latero");
}

TEST(Devices, UnknownBackendIsRefusedWithTheKnownOnes) {
  try {
    parse_backend("winusb");
    FAIL() << "'winusb' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(),
                ::testing::AllOf(::testing::HasSubstr("'winusb'"),
                                 ::testing::HasSubstr("emulated, libusb, hidapi, latero")));
  }
}

}  // namespace
}  // namespace tactile::display
