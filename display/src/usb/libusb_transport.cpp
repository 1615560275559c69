// Vendor-interface transport: control requests on endpoint 0, frames as asynchronous bulk
// transfers on EP 0x01, each ended by a short or zero-length packet (one frame per transfer).
#include <libusb.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "tactile/display/control_codec.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile_fw/usb.h"

namespace tactile::display {

namespace {

// bmRequestType of the vendor requests (usb.h); spelled as numbers because combining
// libusb's separate enums is deprecated in C++20.
constexpr std::uint8_t kVendorIn = 0xC1;
constexpr std::uint8_t kVendorOut = 0x41;

std::string usb_error(int code) {
  if (code == LIBUSB_ERROR_NO_DEVICE) return "the display was unplugged (LIBUSB_ERROR_NO_DEVICE)";
  return std::string(libusb_error_name(code)) + " (" + libusb_strerror(code) + ")";
}

class LibusbTransport final : public Transport {
 public:
  LibusbTransport(const DeviceDescription& device, const UsbTransportOptions& options)
      : options_(options), where_("display at USB " + device.path) {
    if (libusb_init(&ctx_) != 0) throw TransportError("libusb: cannot initialise USB");
    try {
      open(device);
      info_ = decode_device_info(control_in(TFW_USB_REQ_GET_INFO, TFW_INFO_BYTES, "get info"),
                                 Backend::libusb, product_, serial_, "");
    } catch (...) {
      close();
      throw;
    }
  }

  ~LibusbTransport() override { close(); }

  DeviceInfo info() override { return info_; }

  void start(double rate_hz) override {
    check_failure();
    const auto rate = start_rate_value(rate_hz);
    control_out(TFW_USB_REQ_START, rate, "start at " + std::to_string(rate) + " Hz");
  }

  void stop() override {
    check_failure();
    control_out(TFW_USB_REQ_STOP, 0, "stop");
  }

  bool send_frame(std::span<const std::uint8_t> frame) override {
    pump(std::chrono::milliseconds(0));
    check_failure();
    Slot* slot = free_slot();
    if (slot == nullptr) return false;  // device NAKs while its FIFO is full: wait, resend
    slot->data.assign(frame.begin(), frame.end());
    libusb_fill_bulk_transfer(slot->transfer, handle_, TFW_USB_EP_FRAMES_OUT, slot->data.data(),
                              static_cast<int>(slot->data.size()), &LibusbTransport::on_done, this,
                              static_cast<unsigned>(options_.timeout.count()));
    slot->transfer->flags = LIBUSB_TRANSFER_ADD_ZERO_PACKET;
    const int rc = libusb_submit_transfer(slot->transfer);
    if (rc != 0) fail("sending a frame failed: " + usb_error(rc));
    slot->busy = true;
    return true;
  }

  DeviceStatus status() override {
    check_failure();
    return decode_device_status(control_in(TFW_USB_REQ_GET_STATUS, TFW_STATUS_BYTES, "status"));
  }

  void wait(std::chrono::nanoseconds duration) override {
    pump(std::chrono::duration_cast<std::chrono::microseconds>(duration));
    check_failure();
  }

 private:
  struct Slot {
    libusb_transfer* transfer = nullptr;
    std::vector<std::uint8_t> data;
    bool busy = false;
  };

  void open(const DeviceDescription& device) {
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    libusb_device* found = nullptr;
    for (ssize_t i = 0; i < n && found == nullptr; ++i) {
      libusb_device_descriptor desc{};
      if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
      const bool ours = desc.idVendor == TFW_USB_VENDOR_ID && desc.idProduct == TFW_USB_PRODUCT_ID;
      const bool here =
          device.path.empty() || (libusb_get_bus_number(list[i]) == device.bus &&
                                  libusb_get_device_address(list[i]) == device.address);
      if (ours && here) found = list[i];
    }
    int rc = found != nullptr ? libusb_open(found, &handle_) : LIBUSB_ERROR_NOT_FOUND;
    if (n >= 0) libusb_free_device_list(list, 1);
    if (rc != 0) {
      handle_ = nullptr;
      throw TransportError("libusb: cannot open the " + where_ + ": " + usb_error(rc) +
                           (rc == LIBUSB_ERROR_ACCESS ? "; install the udev rules (README)" : ""));
    }
    rc = libusb_claim_interface(handle_, TFW_USB_VENDOR_INTERFACE);
    if (rc != 0) {
      throw TransportError("libusb: cannot claim the vendor interface of the " + where_ + ": " +
                           usb_error(rc));
    }
    claimed_ = true;
    libusb_device_descriptor desc{};
    libusb_get_device_descriptor(libusb_get_device(handle_), &desc);
    product_ = read_string(desc.iProduct);
    serial_ = read_string(desc.iSerialNumber);
    for (int i = 0; i < std::max(1, options_.frames_in_flight); ++i) {
      slots_.push_back(Slot{libusb_alloc_transfer(0), {}, false});
    }
  }

  std::string read_string(std::uint8_t index) {
    unsigned char buf[128];
    const int n =
        index == 0 ? 0 : libusb_get_string_descriptor_ascii(handle_, index, buf, sizeof buf);
    return n > 0 ? std::string(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(n))
                 : std::string();
  }

  std::vector<std::uint8_t> control_in(std::uint8_t request, std::size_t length,
                                       const std::string& what) {
    std::vector<std::uint8_t> reply(length);
    const int rc = libusb_control_transfer(handle_, kVendorIn, request, 0, TFW_USB_VENDOR_INTERFACE,
                                           reply.data(), static_cast<std::uint16_t>(length),
                                           static_cast<unsigned>(options_.timeout.count()));
    if (rc < 0) fail(what + " request failed: " + usb_error(rc));
    reply.resize(static_cast<std::size_t>(rc));
    return reply;
  }

  void control_out(std::uint8_t request, std::uint16_t value, const std::string& what) {
    const int rc =
        libusb_control_transfer(handle_, kVendorOut, request, value, TFW_USB_VENDOR_INTERFACE,
                                nullptr, 0, static_cast<unsigned>(options_.timeout.count()));
    if (rc == LIBUSB_ERROR_PIPE) throw TransportError("the " + where_ + " refused " + what);
    if (rc < 0) fail(what + " request failed: " + usb_error(rc));
  }

  Slot* free_slot() {
    for (auto& s : slots_) {
      if (!s.busy) return &s;
    }
    return nullptr;
  }

  static void LIBUSB_CALL on_done(libusb_transfer* transfer) {
    auto* self = static_cast<LibusbTransport*>(transfer->user_data);
    for (auto& s : self->slots_) {
      if (s.transfer == transfer) s.busy = false;
    }
    if (transfer->status == LIBUSB_TRANSFER_COMPLETED || self->closing_) return;
    if (self->failure_.empty()) {
      self->failure_ =
          transfer->status == LIBUSB_TRANSFER_NO_DEVICE
              ? std::string("the display was unplugged (LIBUSB_TRANSFER_NO_DEVICE)")
          : transfer->status == LIBUSB_TRANSFER_TIMED_OUT
              ? "a frame was not accepted within " +
                    std::to_string(self->options_.timeout.count()) + " ms"
              : std::string("frame transfer failed: ") + libusb_error_name(transfer->status);
    }
  }

  // Runs libusb's event handling (completions) for up to `duration`.
  void pump(std::chrono::microseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    do {
      const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
          end - std::chrono::steady_clock::now());
      timeval tv{};
      tv.tv_sec = static_cast<time_t>(std::max<std::int64_t>(0, left.count()) / 1000000);
      tv.tv_usec = static_cast<suseconds_t>(std::max<std::int64_t>(0, left.count()) % 1000000);
      const int rc = libusb_handle_events_timeout_completed(ctx_, &tv, nullptr);
      if (rc != 0 && rc != LIBUSB_ERROR_INTERRUPTED)
        fail("USB event handling failed: " + usb_error(rc));
    } while (std::chrono::steady_clock::now() < end);
  }

  [[noreturn]] void fail(const std::string& what) {
    throw TransportError("libusb: " + what + " (" + where_ + ")");
  }

  void check_failure() {
    if (!failure_.empty()) fail(failure_);
  }

  void close() {
    closing_ = true;
    if (handle_ != nullptr) {
      for (auto& s : slots_) {
        if (s.busy) libusb_cancel_transfer(s.transfer);
      }
      // Cancelled transfers complete through the event loop; bounded in case the device is gone.
      const auto end = std::chrono::steady_clock::now() + options_.timeout;
      while (std::any_of(slots_.begin(), slots_.end(), [](const Slot& s) { return s.busy; }) &&
             std::chrono::steady_clock::now() < end) {
        timeval tv{0, 10000};
        libusb_handle_events_timeout_completed(ctx_, &tv, nullptr);
      }
    }
    for (auto& s : slots_) {
      // A transfer still in flight is leaked rather than freed under the host controller.
      if (!s.busy) libusb_free_transfer(s.transfer);
    }
    slots_.clear();
    if (handle_ != nullptr) {
      if (claimed_) libusb_release_interface(handle_, TFW_USB_VENDOR_INTERFACE);
      libusb_close(handle_);
      handle_ = nullptr;
    }
    if (ctx_ != nullptr) {
      libusb_exit(ctx_);
      ctx_ = nullptr;
    }
  }

  UsbTransportOptions options_;
  std::string where_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  bool claimed_ = false;
  bool closing_ = false;
  std::string product_;
  std::string serial_;
  DeviceInfo info_;
  std::vector<Slot> slots_;
  std::string failure_;
};

}  // namespace

std::unique_ptr<Transport> open_libusb_transport(const DeviceDescription& device,
                                                 const UsbTransportOptions& options) {
  return std::make_unique<LibusbTransport>(device, options);
}

std::unique_ptr<Transport> open_usb_transport(const DeviceDescription& device,
                                              const UsbTransportOptions& options) {
  switch (device.backend) {
    case Backend::libusb:
      return open_libusb_transport(device, options);
    case Backend::hidapi:
      return open_hidapi_transport(device, options);
    case Backend::emulated:
    case Backend::latero:
      break;
  }
  throw TransportError("'" + to_string(device.backend) + "' is not a USB back end");
}

}  // namespace tactile::display
