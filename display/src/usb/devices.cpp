// USB enumeration through libusb (usbdevfs) and hidapi (hidraw).
#include "tactile/display/devices.hpp"

#include <hidapi.h>
#include <libusb.h>
#include <unistd.h>

#include <cwchar>
#include <string>

namespace tactile::display {

namespace {

std::string read_string(libusb_device_handle* handle, std::uint8_t index) {
  if (index == 0) return {};
  unsigned char buf[256];
  const int n = libusb_get_string_descriptor_ascii(handle, index, buf, sizeof buf);
  return n > 0 ? std::string(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(n))
               : std::string();
}

std::string narrow(const wchar_t* w) {
  std::string out;
  if (w == nullptr) return out;
  for (; *w != L'\0'; ++w) out += (*w >= 32 && *w < 127) ? static_cast<char>(*w) : '?';
  return out;
}

void list_libusb(std::vector<DeviceDescription>& out) {
  libusb_context* ctx = nullptr;
  // No USB subsystem (containers, CI) means no device, not an error.
  if (libusb_init(&ctx) != 0) return;
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
    if (desc.idVendor != kUsbVendorId || desc.idProduct != kUsbProductId) continue;
    DeviceDescription d;
    d.backend = Backend::libusb;
    d.vendor_id = desc.idVendor;
    d.product_id = desc.idProduct;
    d.bus = libusb_get_bus_number(list[i]);
    d.address = libusb_get_device_address(list[i]);
    d.path = std::to_string(d.bus) + ":" + std::to_string(d.address);
    libusb_device_handle* handle = nullptr;
    if (libusb_open(list[i], &handle) == 0) {
      d.accessible = true;
      d.manufacturer = read_string(handle, desc.iManufacturer);
      d.product = read_string(handle, desc.iProduct);
      d.serial = read_string(handle, desc.iSerialNumber);
      libusb_close(handle);
    }
    out.push_back(d);
  }
  if (n >= 0) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
}

void list_hidapi(std::vector<DeviceDescription>& out) {
  if (hid_init() != 0) return;
  hid_device_info* devs = hid_enumerate(kUsbVendorId, kUsbProductId);
  for (hid_device_info* p = devs; p != nullptr; p = p->next) {
    DeviceDescription d;
    d.backend = Backend::hidapi;
    d.vendor_id = p->vendor_id;
    d.product_id = p->product_id;
    d.path = p->path != nullptr ? p->path : "";
    d.interface_number = p->interface_number;
    d.manufacturer = narrow(p->manufacturer_string);
    d.product = narrow(p->product_string);
    d.serial = narrow(p->serial_number);
    // The hidraw back end lists from sysfs without opening the node: ask the node itself.
    d.accessible = !d.path.empty() && access(d.path.c_str(), R_OK | W_OK) == 0;
    out.push_back(d);
  }
  hid_free_enumeration(devs);
  hid_exit();
}

}  // namespace

std::vector<DeviceDescription> list_usb_devices() {
  std::vector<DeviceDescription> out;
  list_libusb(out);
  list_hidapi(out);
  return out;
}

}  // namespace tactile::display
