// HID-interface transport (hosts without a driver): frames split into output reports of 61
// payload bytes, control requests as feature reports (docs/protocol.md, "HID interface").
// Linked against hidapi's hidraw back end: each report is a write() to /dev/hidrawN, which the
// kernel's usbhid driver sends as an interrupt OUT transfer, and each feature report an ioctl
// it sends as a GET_REPORT/SET_REPORT control transfer.
#include <hidapi.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cwchar>
#include <string>
#include <thread>
#include <vector>

#include "tactile/display/control_codec.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile_fw/usb.h"

namespace tactile::display {

namespace {

std::string narrow(const wchar_t* w) {
  std::string out;
  if (w == nullptr) return out;
  for (; *w != L'\0'; ++w) out += (*w >= 32 && *w < 127) ? static_cast<char>(*w) : '?';
  return out;
}

class HidapiTransport final : public Transport {
 public:
  HidapiTransport(const DeviceDescription& device, const UsbTransportOptions& options)
      : options_(options), where_("display at HID " + device.path) {
    if (hid_init() != 0) throw TransportError("hidapi: cannot initialise");
    dev_ = hid_open_path(device.path.c_str());
    if (dev_ == nullptr) {
      const std::string why = narrow(hid_error(nullptr));
      hid_exit();
      throw TransportError("hidapi: cannot open the " + where_ + (why.empty() ? "" : ": " + why) +
                           " (unplugged, or no permission: install the udev rules)");
    }
    try {
      wchar_t buf[128];
      std::string product;
      std::string serial;
      if (hid_get_product_string(dev_, buf, 128) == 0) product = narrow(buf);
      if (hid_get_serial_number_string(dev_, buf, 128) == 0) serial = narrow(buf);
      info_ = decode_device_info(feature(TFW_HID_REPORT_INFO, TFW_INFO_BYTES, "get info"),
                                 Backend::hidapi, product, serial, "");
    } catch (...) {
      close();
      throw;
    }
  }

  ~HidapiTransport() override { close(); }

  DeviceInfo info() override { return info_; }

  void start(double rate_hz) override {
    command(TFW_USB_REQ_START, start_rate_value(rate_hz), "start");
  }

  void stop() override { command(TFW_USB_REQ_STOP, 0, "stop"); }

  // Each report is an interrupt OUT transfer the device NAKs while its FIFO is full, so a
  // write returns once the device took the chunk, or fails: ENODEV once unplugged, or after
  // the kernel's own 5 s transfer timeout (hidraw writes have no timeout of their own).
  bool send_frame(std::span<const std::uint8_t> frame) override {
    std::uint8_t report[TFW_HID_REPORT_BYTES];
    for (std::size_t at = 0; at < frame.size() || at == 0; at += TFW_HID_CHUNK_PAYLOAD) {
      const std::size_t n = std::min<std::size_t>(TFW_HID_CHUNK_PAYLOAD, frame.size() - at);
      std::fill(std::begin(report), std::end(report), std::uint8_t{0});
      report[0] = TFW_HID_REPORT_FRAME;
      report[1] = static_cast<std::uint8_t>((at == 0 ? TFW_HID_CHUNK_FIRST : 0u) |
                                            (at + n >= frame.size() ? TFW_HID_CHUNK_LAST : 0u));
      report[2] = static_cast<std::uint8_t>(n);
      std::copy_n(frame.begin() + static_cast<std::ptrdiff_t>(at), n, report + 3);
      if (hid_write(dev_, report, sizeof report) < 0) fail("sending a frame failed");
      if (frame.empty()) break;
    }
    return true;
  }

  DeviceStatus status() override {
    return decode_device_status(feature(TFW_HID_REPORT_STATUS, TFW_STATUS_BYTES, "status"));
  }

  void wait(std::chrono::nanoseconds duration) override { std::this_thread::sleep_for(duration); }

 private:
  std::vector<std::uint8_t> feature(std::uint8_t id, std::size_t length, const std::string& what) {
    std::vector<std::uint8_t> buf(length + 1);
    buf[0] = id;
    const int n = hid_get_feature_report(dev_, buf.data(), buf.size());
    if (n < 1) fail(what + " request failed");
    // hidapi counts the report ID in the returned length.
    return {buf.begin() + 1,
            buf.begin() + std::min<std::ptrdiff_t>(n, static_cast<std::ptrdiff_t>(buf.size()))};
  }

  void command(std::uint8_t request, std::uint16_t value, const std::string& what) {
    std::uint8_t report[1 + TFW_HID_COMMAND_BYTES] = {TFW_HID_REPORT_COMMAND, request, 0,
                                                      static_cast<std::uint8_t>(value & 0xFF),
                                                      static_cast<std::uint8_t>(value >> 8)};
    if (hid_send_feature_report(dev_, report, sizeof report) < 0) {
      fail(what + " request failed or was refused");
    }
  }

  [[noreturn]] void fail(const std::string& what) {
    // hidraw gives strerror() text ("No such device"); other back ends may have none.
    const std::string e = dev_ != nullptr ? narrow(hid_error(dev_)) : std::string();
    const bool useful =
        !e.empty() && e != "Success" && e.find("not implemented") == std::string::npos;
    // The kernel removed the device: ENODEV for a call after the removal, ESHUTDOWN for a
    // transfer it cut short; hidapi may put the call before it ("ioctl (GFEATURE): ...").
    // Say so as the libusb transport does.
    if (e.ends_with(std::strerror(ENODEV)) || e.ends_with(std::strerror(ESHUTDOWN))) {
      throw TransportError("hidapi: " + what + ": the display was unplugged (" + e + ") (" +
                           where_ + ")");
    }
    throw TransportError("hidapi: " + what + (useful ? ": " + e : std::string()) + " (" + where_ +
                         "; unplugged?)");
  }

  void close() {
    if (dev_ != nullptr) hid_close(dev_);
    dev_ = nullptr;
    hid_exit();
  }

  UsbTransportOptions options_;
  std::string where_;
  hid_device* dev_ = nullptr;
  DeviceInfo info_;
};

}  // namespace

std::unique_ptr<Transport> open_hidapi_transport(const DeviceDescription& device,
                                                 const UsbTransportOptions& options) {
  return std::make_unique<HidapiTransport>(device, options);
}

}  // namespace tactile::display
