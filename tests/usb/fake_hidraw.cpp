#include "fake_hidraw.hpp"

#include <linux/hidraw.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <umockdev.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "fake_firmware.hpp"

namespace tactile::test {

namespace {

// usbhid's class requests on endpoint 0 (HID 1.11, 7.2), interface 1.
constexpr std::uint8_t kGetReport = 0x01;
constexpr std::uint8_t kSetReport = 0x09;
constexpr std::uint8_t kFeature = 0x03;

// The kernel's USB_CTRL_SET_TIMEOUT: how long usb_interrupt_msg() waits for the device.
constexpr auto kWriteTimeout = std::chrono::seconds(5);

}  // namespace

struct FakeHidraw::Impl {
  UMockdevTestbed* testbed = nullptr;
  UMockdevIoctlBase* handler = nullptr;
  std::string usb_syspath;
  mutable std::mutex mutex;
  FakeFirmware fw{"UMOCK-HID-1"};
  std::vector<std::vector<std::uint8_t>> reports;
  bool unplugged = false;

  // A feature report through the firmware's endpoint 0; `buf` starts with the report ID.
  long feature(bool get, std::uint8_t* buf, std::size_t len) {
    const auto n = static_cast<std::uint16_t>(len);
    const std::uint8_t setup[8] = {static_cast<std::uint8_t>(get ? 0xA1 : 0x21),
                                   get ? kGetReport : kSetReport,
                                   buf[0],
                                   kFeature,
                                   TFW_USB_HID_INTERFACE,
                                   0,
                                   static_cast<std::uint8_t>(n & 0xFF),
                                   static_cast<std::uint8_t>(n >> 8)};
    return fw.control(setup, buf);
  }

  void on_ioctl(UMockdevIoctlClient* client) {
    std::lock_guard<std::mutex> lock(mutex);
    if (unplugged) return umockdev_ioctl_client_complete(client, -1, ENODEV);
    fw.advance();
    const unsigned long request = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    const std::size_t size = _IOC_SIZE(request);
    if (_IOC_TYPE(request) != 'H') return umockdev_ioctl_client_complete(client, -1, ENOTTY);
    UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, size, nullptr);
    if (d == nullptr) return umockdev_ioctl_client_complete(client, -1, EFAULT);
    auto* data = static_cast<std::uint8_t*>(d->data);
    long result = 0;
    int error = 0;
    const std::vector<std::uint8_t> rdesc = fw.hid_report_descriptor();
    if (request == HIDIOCGRDESCSIZE) {
      const int n = static_cast<int>(rdesc.size());
      std::memcpy(data, &n, sizeof n);
    } else if (request == HIDIOCGRDESC) {
      hidraw_report_descriptor desc{};
      std::memcpy(&desc, data, sizeof desc.size);
      if (desc.size < rdesc.size()) {
        result = -1;
        error = EINVAL;
      } else {
        desc.size = static_cast<__u32>(rdesc.size());
        std::copy(rdesc.begin(), rdesc.end(), desc.value);
        std::memcpy(data, &desc, sizeof desc);
      }
    } else if (request == HIDIOCGRAWINFO) {
      const hidraw_devinfo info{BUS_USB, 0x1209, 0x0001};
      std::memcpy(data, &info, sizeof info);
    } else if (_IOC_NR(request) == _IOC_NR(HIDIOCGFEATURE(0)) ||
               _IOC_NR(request) == _IOC_NR(HIDIOCSFEATURE(0))) {
      const bool get = _IOC_NR(request) == _IOC_NR(HIDIOCGFEATURE(0));
      result = size == 0 ? -1 : feature(get, data, size);
      if (result < 0) error = EPIPE;  // the device stalled the request
    } else {
      result = -1;
      error = ENOTTY;
    }
    umockdev_ioctl_data_unref(d);
    umockdev_ioctl_client_complete(client, result, error);
  }

  // One output report: an interrupt OUT transfer the firmware NAKs while its FIFO is full.
  void on_write(UMockdevIoctlClient* client) {
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    const auto* bytes = static_cast<const std::uint8_t*>(arg->data);
    const auto len = static_cast<std::size_t>(arg->data_len);
    const auto deadline = std::chrono::steady_clock::now() + kWriteTimeout;
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (unplugged) return umockdev_ioctl_client_complete(client, -1, ENODEV);
        fw.advance();
        if (fw.out_ready(TFW_USB_EP_HID_OUT)) {
          reports.emplace_back(bytes, bytes + len);
          tfw_usb_hid_out(&fw.usb, bytes, static_cast<std::uint16_t>(len));
          return umockdev_ioctl_client_complete(client, static_cast<long>(len), 0);
        }
      }
      if (std::chrono::steady_clock::now() > deadline) {
        return umockdev_ioctl_client_complete(client, -1, ETIMEDOUT);
      }
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }

  // An input report (fill report) when the firmware has one; hidraw reads never block here.
  void on_read(UMockdevIoctlClient* client) {
    std::lock_guard<std::mutex> lock(mutex);
    if (unplugged) return umockdev_ioctl_client_complete(client, -1, ENODEV);
    fw.advance();
    const std::vector<std::uint8_t> report = fw.take_hid_in();
    if (report.empty()) return umockdev_ioctl_client_complete(client, -1, EAGAIN);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    const std::size_t n = std::min(report.size(), static_cast<std::size_t>(arg->data_len));
    umockdev_ioctl_data_update(arg, 0, const_cast<std::uint8_t*>(report.data()),
                               static_cast<gint>(n));
    umockdev_ioctl_client_complete(client, static_cast<long>(n), 0);
  }

  static gboolean ioctl_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    static_cast<Impl*>(self)->on_ioctl(client);
    return TRUE;
  }
  static gboolean write_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    static_cast<Impl*>(self)->on_write(client);
    return TRUE;
  }
  static gboolean read_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    static_cast<Impl*>(self)->on_read(client);
    return TRUE;
  }
};

FakeHidraw::FakeHidraw() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.testbed = umockdev_testbed_new();
  m.handler = umockdev_ioctl_base_new();
  g_signal_connect_after(m.handler, "handle-ioctl", G_CALLBACK(&Impl::ioctl_cb), &m);
  g_signal_connect_after(m.handler, "handle-write", G_CALLBACK(&Impl::write_cb), &m);
  g_signal_connect_after(m.handler, "handle-read", G_CALLBACK(&Impl::read_cb), &m);
  if (!umockdev_testbed_attach_ioctl(m.testbed, kDevnode, m.handler, nullptr)) {
    throw std::runtime_error(
        "umockdev: cannot attach the ioctl handler (run under umockdev-wrapper)");
  }
  // The sysfs chain of a real composite display with usbhid bound to interface 1.
  gchar* usb = umockdev_testbed_add_device(
      m.testbed, "usb", "usb1/1-1", nullptr, "idVendor", "1209", "idProduct", "0001", "bcdDevice",
      "0100", "manufacturer", "tactile-movies", "product", "Tactile display", "serial",
      "UMOCK-HID-1", "busnum", "1", "devnum", "3", "speed", "12", nullptr, "DEVTYPE", "usb_device",
      "BUSNUM", "001", "DEVNUM", "003", nullptr);
  gchar* intf = umockdev_testbed_add_device(m.testbed, "usb", "1-1:1.1", usb, "bInterfaceNumber",
                                            "01", "bInterfaceClass", "03", nullptr, "DEVTYPE",
                                            "usb_interface", "DRIVER", "usbhid", nullptr);
  gchar* hid = umockdev_testbed_add_device(
      m.testbed, "hid", "0003:1209:0001.0001", intf, nullptr, "DRIVER", "hid-generic", "HID_ID",
      "0003:00001209:00000001", "HID_NAME", "tactile-movies Tactile display", "HID_PHYS",
      "usb-0000:00:14.0-1/input1", "HID_UNIQ", "UMOCK-HID-1", nullptr);
  std::vector<std::uint8_t> rdesc = m.fw.hid_report_descriptor();
  umockdev_testbed_set_attribute_binary(m.testbed, hid, "report_descriptor", rdesc.data(),
                                        static_cast<gint>(rdesc.size()));
  gchar* raw =
      umockdev_testbed_add_device(m.testbed, "hidraw", "hidraw0", hid, "dev", "247:0", nullptr,
                                  "DEVNAME", kDevnode, "MAJOR", "247", "MINOR", "0", nullptr);
  // hidapi reads <hidraw>/device/uevent and <hidraw>/device/report_descriptor.
  if (raw != nullptr) umockdev_testbed_set_attribute_link(m.testbed, raw, "device", "..");
  // The node itself (add_from_string's "N:" line does this; add_device does not).
  gchar* root = umockdev_testbed_get_root_dir(m.testbed);
  const std::string node = std::string(root) + kDevnode;
  g_free(root);
  const bool made = g_file_set_contents(node.c_str(), "", 0, nullptr) != FALSE;
  const bool ok = usb != nullptr && intf != nullptr && hid != nullptr && raw != nullptr && made;
  if (usb != nullptr) m.usb_syspath = usb;
  g_free(raw);
  g_free(hid);
  g_free(intf);
  g_free(usb);
  if (!ok) throw std::runtime_error("umockdev: cannot add the fake hidraw display");
}

FakeHidraw::~FakeHidraw() {
  g_clear_object(&impl_->handler);
  g_clear_object(&impl_->testbed);
}

std::vector<std::vector<std::uint8_t>> FakeHidraw::output_reports() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->reports;
}

std::vector<std::int16_t> FakeHidraw::outputs() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->fw.outputs();
}

void FakeHidraw::unplug() {
  Impl& m = *impl_;
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    if (m.unplugged) return;
    m.unplugged = true;
  }
  umockdev_testbed_uevent(m.testbed, m.usb_syspath.c_str(), "remove");
  umockdev_testbed_remove_device(m.testbed, m.usb_syspath.c_str());
}

}  // namespace tactile::test
