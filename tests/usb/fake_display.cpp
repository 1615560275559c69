#include "fake_display.hpp"

#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>

#include "fake_firmware.hpp"

namespace tactile::test {

struct FakeDisplay::Impl {
  UMockdevTestbed* testbed = nullptr;
  UMockdevIoctlBase* handler = nullptr;
  mutable std::mutex mutex;
  FakeFirmware fw{"UMOCK-1"};
  std::deque<UMockdevIoctlData*> pending_out;  // OUT URBs the device is NAKing
  std::deque<UMockdevIoctlData*> pending_in;   // interrupt IN URBs waiting for a report
  std::deque<UMockdevIoctlData*> completed;    // ready to be reaped
  std::vector<std::vector<std::uint8_t>> bulk;
  bool unplugged = false;

  static usbdevfs_urb* urb_of(UMockdevIoctlData* d) {
    return reinterpret_cast<usbdevfs_urb*>(d->data);
  }

  void advance() {
    fw.advance();
    deliver_out();
    deliver_in();
  }

  // Feeds waiting OUT URBs to the firmware while it accepts them.
  void deliver_out() {
    while (!pending_out.empty()) {
      UMockdevIoctlData* d = pending_out.front();
      usbdevfs_urb* urb = urb_of(d);
      const int ep = urb->endpoint & 3;
      if (!fw.out_ready(static_cast<std::uint8_t>(ep))) return;
      pending_out.pop_front();
      // Shared address space: the client's buffer is readable here (as in libusb's tests).
      const auto* bytes = static_cast<const std::uint8_t*>(urb->buffer);
      const auto len = static_cast<std::size_t>(urb->buffer_length);
      if (urb->type == USBDEVFS_URB_TYPE_BULK) {
        bulk.emplace_back(bytes, bytes + len);
        std::size_t at = 0;
        for (;;) {
          const std::size_t n = std::min<std::size_t>(TFW_USB_BULK_PACKET_FS, len - at);
          tfw_usb_bulk_out(&fw.usb, bytes + at, static_cast<std::uint16_t>(n));
          at += n;
          if (n < TFW_USB_BULK_PACKET_FS) break;
          if (at == len && !(urb->flags & USBDEVFS_URB_ZERO_PACKET)) break;
        }
      } else {
        tfw_usb_hid_out(&fw.usb, bytes, static_cast<std::uint16_t>(len));
      }
      urb->actual_length = urb->buffer_length;
      urb->status = 0;
      completed.push_back(d);
    }
  }

  void deliver_in() {
    while (!pending_in.empty()) {
      const std::vector<std::uint8_t> report = fw.take_hid_in();
      if (report.empty()) return;
      UMockdevIoctlData* d = pending_in.front();
      pending_in.pop_front();
      usbdevfs_urb* urb = urb_of(d);
      const std::size_t n =
          std::min<std::size_t>(report.size(), static_cast<std::size_t>(urb->buffer_length));
      std::memcpy(urb->buffer, report.data(), n);
      urb->actual_length = static_cast<int>(n);
      urb->status = 0;
      completed.push_back(d);
    }
  }

  void control(UMockdevIoctlData* d) {
    usbdevfs_urb* urb = urb_of(d);
    auto* buffer = static_cast<std::uint8_t*>(urb->buffer);
    const int n = fw.control(buffer, buffer + 8);
    urb->status = n < 0 ? -EPIPE : 0;
    urb->actual_length = n < 0 ? 0 : n;
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
  m.testbed = umockdev_testbed_new();
  m.handler = umockdev_ioctl_base_new();
  g_signal_connect_after(m.handler, "handle-ioctl", G_CALLBACK(&Impl::ioctl_cb), &m);
  if (!umockdev_testbed_attach_ioctl(m.testbed, "/dev/bus/usb/001/002", m.handler, nullptr)) {
    throw std::runtime_error(
        "umockdev: cannot attach the ioctl handler (run under umockdev-wrapper)");
  }
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
      m.fw.descriptors_hex() + "\n";
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

std::vector<std::int16_t> FakeDisplay::outputs() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->fw.outputs();
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
