#include "fake_display.hpp"

#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>

#include "device_config.h"  // tests/firmware/target: the STReSS-like test device
#include "tactile_fw/usb.h"

namespace tactile::test {

namespace {

std::string hex(const std::uint8_t* d, std::size_t n) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    s += digits[d[i] >> 4];
    s += digits[d[i] & 15];
  }
  return s;
}

}  // namespace

struct FakeDisplay::Impl {
  UMockdevTestbed* testbed = nullptr;
  UMockdevIoctlBase* handler = nullptr;
  mutable std::mutex mutex;
  tfw_device dev{};
  tfw_usb usb{};
  bool ready[3] = {true, true, true};  // OUT endpoints, by number
  std::vector<std::uint8_t> ep0_reply;
  bool ep0_stalled = false;
  std::vector<std::uint8_t> hid_in;            // latest input report offered by the firmware
  std::deque<UMockdevIoctlData*> pending_out;  // OUT URBs the device is NAKing
  std::deque<UMockdevIoctlData*> pending_in;   // interrupt IN URBs waiting for a report
  std::deque<UMockdevIoctlData*> completed;    // ready to be reaped
  std::vector<std::vector<std::uint8_t>> bulk;
  std::vector<std::uint8_t> hid_partial;
  std::vector<std::vector<std::uint8_t>> hid;
  std::chrono::steady_clock::time_point last_tick = std::chrono::steady_clock::now();
  bool unplugged = false;

  static int dcd_write(void* context, std::uint8_t ep, const std::uint8_t* data,
                       std::uint16_t len) {
    auto* self = static_cast<Impl*>(context);
    if (ep == 0x80) self->ep0_reply.assign(data, data + len);
    if (ep == TFW_USB_EP_HID_IN) self->hid_in.assign(data, data + len);
    return 1;
  }
  static void dcd_stall(void* context, std::uint8_t) {
    static_cast<Impl*>(context)->ep0_stalled = true;
  }
  static void dcd_ready(void* context, std::uint8_t ep, int ready) {
    static_cast<Impl*>(context)->ready[ep & 3] = ready != 0;
  }

  static usbdevfs_urb* urb_of(UMockdevIoctlData* d) {
    return reinterpret_cast<usbdevfs_urb*>(d->data);
  }

  // Plays the ticks that real time says have passed since the last look (at most 100 per
  // look, so a slow host sees underruns rather than a stall).
  void advance() {
    const auto now = std::chrono::steady_clock::now();
    const double period_s = 1.0 / dev.config.rate_hz;
    int ticks = 0;
    while (std::chrono::duration<double>(now - last_tick).count() >= period_s && ticks < 100) {
      tfw_usb_tick(&usb);
      last_tick += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(period_s));
      ++ticks;
    }
    if (ticks == 100) last_tick = now;
    deliver_out();
    deliver_in();
  }

  // Feeds waiting OUT URBs to the firmware while it accepts them.
  void deliver_out() {
    while (!pending_out.empty()) {
      UMockdevIoctlData* d = pending_out.front();
      usbdevfs_urb* urb = urb_of(d);
      const int ep = urb->endpoint & 3;
      if (!ready[ep]) return;
      pending_out.pop_front();
      // Shared address space: the client's buffer is readable here (as in libusb's tests).
      const auto* bytes = static_cast<const std::uint8_t*>(urb->buffer);
      const auto len = static_cast<std::size_t>(urb->buffer_length);
      if (urb->type == USBDEVFS_URB_TYPE_BULK) {
        bulk.emplace_back(bytes, bytes + len);
        std::size_t at = 0;
        for (;;) {
          const std::size_t n = std::min<std::size_t>(TFW_USB_BULK_PACKET_FS, len - at);
          tfw_usb_bulk_out(&usb, bytes + at, static_cast<std::uint16_t>(n));
          at += n;
          if (n < TFW_USB_BULK_PACKET_FS) break;
          if (at == len && !(urb->flags & USBDEVFS_URB_ZERO_PACKET)) break;
        }
      } else {
        record_hid(bytes, len);
        tfw_usb_hid_out(&usb, bytes, static_cast<std::uint16_t>(len));
      }
      urb->actual_length = urb->buffer_length;
      urb->status = 0;
      completed.push_back(d);
    }
  }

  void deliver_in() {
    while (!pending_in.empty() && !hid_in.empty()) {
      UMockdevIoctlData* d = pending_in.front();
      pending_in.pop_front();
      usbdevfs_urb* urb = urb_of(d);
      const std::size_t n =
          std::min<std::size_t>(hid_in.size(), static_cast<std::size_t>(urb->buffer_length));
      std::memcpy(urb->buffer, hid_in.data(), n);
      urb->actual_length = static_cast<int>(n);
      urb->status = 0;
      hid_in.clear();
      completed.push_back(d);
    }
  }

  void record_hid(const std::uint8_t* r, std::size_t len) {
    if (len < 3 || r[0] != TFW_HID_REPORT_FRAME) return;
    if (r[1] & TFW_HID_CHUNK_FIRST) hid_partial.clear();
    hid_partial.insert(hid_partial.end(), r + 3, r + 3 + std::min<std::size_t>(r[2], len - 3));
    if (r[1] & TFW_HID_CHUNK_LAST) hid.push_back(hid_partial);
  }

  void control(UMockdevIoctlData* d) {
    usbdevfs_urb* urb = urb_of(d);
    auto* buffer = static_cast<std::uint8_t*>(urb->buffer);
    const std::uint16_t w_length = static_cast<std::uint16_t>(buffer[6] | (buffer[7] << 8));
    const bool in = (buffer[0] & 0x80) != 0;
    ep0_reply.clear();
    ep0_stalled = false;
    tfw_usb_setup(&usb, buffer, buffer + 8, in ? 0 : w_length);
    if (ep0_stalled) {
      urb->status = -EPIPE;
      urb->actual_length = 0;
    } else {
      const std::size_t n = std::min<std::size_t>(ep0_reply.size(), w_length);
      if (in) std::memcpy(buffer + 8, ep0_reply.data(), n);
      urb->status = 0;
      urb->actual_length = static_cast<int>(in ? n : w_length);
    }
    completed.push_back(d);
  }

  gboolean on_ioctl(UMockdevIoctlClient* client) {
    std::lock_guard<std::mutex> lock(mutex);
    const gulong request = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    switch (request) {
      case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
        *reinterpret_cast<guint32*>(d->data) = USBDEVFS_CAP_ZERO_PACKET |
                                               USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                                               USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
        umockdev_ioctl_data_unref(d);
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      }
      case USBDEVFS_GETDRIVER:
        umockdev_ioctl_client_complete(client, -1, ENODATA);  // no kernel driver bound
        return TRUE;
      case USBDEVFS_CLAIMINTERFACE:
      case USBDEVFS_RELEASEINTERFACE:
      case USBDEVFS_CLEAR_HALT:
      case USBDEVFS_RESET:
      case USBDEVFS_RESETEP:
      case USBDEVFS_SETINTERFACE:
      case USBDEVFS_IOCTL:
      case USBDEVFS_DISCONNECT_CLAIM:
        if (unplugged) {
          umockdev_ioctl_client_complete(client, -1, ENODEV);
        } else {
          umockdev_ioctl_client_complete(client, 0, 0);
        }
        return TRUE;
      case USBDEVFS_SUBMITURB: {
        if (unplugged) {
          umockdev_ioctl_client_complete(client, -1, ENODEV);
          return TRUE;
        }
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
        usbdevfs_urb* urb = urb_of(d);
        if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
          control(d);
        } else if (urb->endpoint & 0x80) {
          pending_in.push_back(d);
        } else {
          pending_out.push_back(d);
        }
        advance();
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      }
      case USBDEVFS_DISCARDURB: {
        const void* addr = *reinterpret_cast<void* const*>(arg->data);
        for (auto* queue : {&pending_out, &pending_in}) {
          for (auto it = queue->begin(); it != queue->end(); ++it) {
            if (reinterpret_cast<const void*>((*it)->client_addr) == addr) {
              urb_of(*it)->status = -ENOENT;
              urb_of(*it)->actual_length = 0;
              completed.push_back(*it);
              queue->erase(it);
              umockdev_ioctl_client_complete(client, 0, 0);
              return TRUE;
            }
          }
        }
        umockdev_ioctl_client_complete(client, -1, EINVAL);
        return TRUE;
      }
      case USBDEVFS_REAPURB:
      case USBDEVFS_REAPURBNDELAY: {
        if (!unplugged) advance();
        if (completed.empty()) {
          umockdev_ioctl_client_complete(client, -1, unplugged ? ENODEV : EAGAIN);
          return TRUE;
        }
        UMockdevIoctlData* d = completed.front();
        completed.pop_front();
        UMockdevIoctlData* ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
        umockdev_ioctl_data_set_ptr(ptr, 0, d);
        umockdev_ioctl_data_unref(ptr);
        umockdev_ioctl_data_unref(d);
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      }
      default:
        return FALSE;
    }
  }

  static gboolean ioctl_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<Impl*>(self)->on_ioctl(client);
  }
};

FakeDisplay::FakeDisplay() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const tfw_config config = tfw_test_stress_config();
  if (tfw_device_init(&m.dev, &config, nullptr) != TFW_CONFIG_OK) {
    throw std::logic_error("fake display: bad firmware configuration");
  }
  const tfw_usb_dcd dcd{&m, &Impl::dcd_write, &Impl::dcd_stall, &Impl::dcd_ready};
  tfw_usb_init(&m.usb, &m.dev, &dcd, TFW_USB_FULL_SPEED, "UMOCK-1");
  // The kernel configures a device when it enumerates it; do the same.
  const std::uint8_t set_configuration[8] = {0x00, 9, 1, 0, 0, 0, 0, 0};
  tfw_usb_setup(&m.usb, set_configuration, nullptr, 0);

  m.testbed = umockdev_testbed_new();
  m.handler = umockdev_ioctl_base_new();
  g_signal_connect_after(m.handler, "handle-ioctl", G_CALLBACK(&Impl::ioctl_cb), &m);
  if (!umockdev_testbed_attach_ioctl(m.testbed, "/dev/bus/usb/001/002", m.handler, nullptr)) {
    throw std::runtime_error(
        "umockdev: cannot attach the ioctl handler (run under umockdev-wrapper)");
  }
  const std::uint8_t* d = nullptr;
  const std::uint16_t device_len = tfw_usb_descriptor(&m.usb, TFW_USB_DESC_DEVICE, 0, &d);
  std::string descriptors = hex(d, device_len);
  const std::uint16_t config_len = tfw_usb_descriptor(&m.usb, TFW_USB_DESC_CONFIGURATION, 0, &d);
  descriptors += hex(d, config_len);
  const std::string sysfs =
      "P: /devices/usb1/1-1\n"
      "N: bus/usb/001/002\n"
      "E: SUBSYSTEM=usb\n"
      "E: DRIVER=usb\n"
      "E: BUSNUM=001\n"
      "E: DEVNUM=002\n"
      "E: DEVNAME=/dev/bus/usb/001/002\n"
      "E: DEVTYPE=usb_device\n"
      "A: bConfigurationValue=1\\n\n"
      "A: busnum=1\\n\n"
      "A: devnum=2\\n\n"
      "A: speed=12\\n\n"
      "H: descriptors=" +
      descriptors + "\n";
  if (!umockdev_testbed_add_from_string(m.testbed, sysfs.c_str(), nullptr)) {
    throw std::runtime_error("umockdev: cannot add the fake display");
  }
}

FakeDisplay::~FakeDisplay() {
  Impl& m = *impl_;
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    for (auto* q : {&m.pending_out, &m.pending_in, &m.completed}) {
      for (auto* d : *q) umockdev_ioctl_data_unref(d);
      q->clear();
    }
  }
  g_clear_object(&m.handler);
  g_clear_object(&m.testbed);
}

std::vector<std::vector<std::uint8_t>> FakeDisplay::bulk_transfers() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->bulk;
}

std::vector<std::vector<std::uint8_t>> FakeDisplay::hid_frames() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->hid;
}

void FakeDisplay::unplug() {
  Impl& m = *impl_;
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    m.unplugged = true;
    for (auto* q : {&m.pending_out, &m.pending_in}) {
      for (auto* d : *q) {
        Impl::urb_of(d)->status = -ENODEV;
        Impl::urb_of(d)->actual_length = 0;
        m.completed.push_back(d);
      }
      q->clear();
    }
  }
  umockdev_testbed_uevent(m.testbed, "/sys/devices/usb1/1-1", "remove");
}

}  // namespace tactile::test
