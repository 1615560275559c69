// Test client run inside the QEMU guest (tests/vm): the project's own USB code (device listing,
// the libusb and hidapi transports, the player) against the display that the guest's kernel
// enumerated on its xHCI controller. Prints "VM: key=value" lines on the serial console for
// the host harness (vm_harness.cpp) to check.
//
//   vm_client enumerate                 what the kernel made of the device (sysfs, hidraw)
//   vm_client play libusb|hidapi RATE SECONDS
//                                       plays a RATE Hz movie of SECONDS through the back end;
//                                       exit 1 with "VM: error=..." when the link fails
//   vm_client replay libusb|hidapi RATE SECONDS
//                                       the same, waiting longer for the display to come back
#include <hidapi.h>
#include <libusb.h>
#include <sys/resource.h>
#include <unistd.h>

#include <dirent.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tactile/display/devices.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile_fw/control.h"
#include "tactile_fw/usb.h"

namespace td = tactile::display;

namespace {

double uptime_s() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::string s;
  std::getline(in, s);
  return s;
}

std::vector<std::string> list_dir(const std::string& path) {
  std::vector<std::string> out;
  if (DIR* d = opendir(path.c_str())) {
    while (dirent* e = readdir(d)) {
      if (e->d_name[0] != '.') out.emplace_back(e->d_name);
    }
    closedir(d);
  }
  return out;
}

// The sysfs folder of our display, or "" when the kernel has not (yet) enumerated it.
std::string find_usb_device() {
  for (const auto& name : list_dir("/sys/bus/usb/devices")) {
    const std::string dir = "/sys/bus/usb/devices/" + name;
    if (read_file(dir + "/idVendor") == "1209" && read_file(dir + "/idProduct") == "0001") {
      return dir;
    }
  }
  return {};
}

// Waits for the display with a bound hidraw node (the last step of enumeration).
std::string wait_for_device(double seconds) {
  const double end = uptime_s() + seconds;
  while (uptime_s() < end) {
    const std::string dir = find_usb_device();
    if (!dir.empty()) {
      const std::string name = dir.substr(dir.rfind('/') + 1);
      for (const auto& hid : list_dir(dir + "/" + name + ":1.1")) {
        if (!list_dir(dir + "/" + name + ":1.1/" + hid + "/hidraw").empty()) return dir;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return find_usb_device();
}

int enumerate() {
  const std::string dir = wait_for_device(20);
  if (dir.empty()) {
    std::printf("VM: error=no USB device 1209:0001 enumerated\n");
    return 1;
  }
  const std::string name = dir.substr(dir.rfind('/') + 1);
  std::printf("VM: enumerated_at_s=%.3f\n", uptime_s());
  std::printf("VM: vid=%s pid=%s\n", read_file(dir + "/idVendor").c_str(),
              read_file(dir + "/idProduct").c_str());
  std::printf("VM: manufacturer=%s\n", read_file(dir + "/manufacturer").c_str());
  std::printf("VM: product=%s\n", read_file(dir + "/product").c_str());
  std::printf("VM: serial=%s\n", read_file(dir + "/serial").c_str());
  std::printf("VM: speed=%s\n", read_file(dir + "/speed").c_str());
  std::printf("VM: interfaces=%s\n", read_file(dir + "/bNumInterfaces").c_str());
  for (int i = 0; i < 2; ++i) {
    const std::string intf = dir + "/" + name + ":1." + std::to_string(i);
    std::string driver;
    char link[256] = {0};
    const ssize_t n = readlink((intf + "/driver").c_str(), link, sizeof link - 1);
    if (n > 0) driver = std::string(link, static_cast<std::size_t>(n));
    driver = driver.empty() ? "none" : driver.substr(driver.rfind('/') + 1);
    std::printf("VM: if%d class=%s endpoints=%s driver=%s\n", i,
                read_file(intf + "/bInterfaceClass").c_str(),
                read_file(intf + "/bNumEndpoints").c_str(), driver.c_str());
    for (const auto& ep : list_dir(intf)) {
      if (ep.rfind("ep_", 0) != 0) continue;
      std::printf("VM: if%d %s type=%s interval=%s max_packet=%s\n", i, ep.c_str(),
                  read_file(intf + "/" + ep + "/type").c_str(),
                  read_file(intf + "/" + ep + "/interval").c_str(),
                  read_file(intf + "/" + ep + "/wMaxPacketSize").c_str());
    }
  }
  for (const auto& node : list_dir("/sys/class/hidraw")) {
    std::printf("VM: hidraw=/dev/%s exists=%d\n", node.c_str(),
                access(("/dev/" + node).c_str(), R_OK | W_OK) == 0 ? 1 : 0);
  }
  // The project's own listing: both back ends, each with the strings read from the device.
  for (const auto& d : td::list_usb_devices()) {
    std::printf("VM: listed backend=%s path=%s interface=%d product=%s serial=%s accessible=%d\n",
                td::to_string(d.backend).c_str(), d.path.c_str(), d.interface_number,
                d.product.c_str(), d.serial.c_str(), d.accessible ? 1 : 0);
  }
  return 0;
}

// A movie of the device's geometry: every contactor on a slow sine of its own phase.
tactile::movie::TactileMovie make_movie(const td::DeviceInfo& info, double rate_hz,
                                        double seconds) {
  tactile::movie::TactileMovie movie;
  movie.layout = info.layout;
  movie.rate_hz = rate_hz;
  movie.frame_count = static_cast<std::int32_t>(std::lround(rate_hz * seconds));
  const auto n = static_cast<std::size_t>(movie.layout.contactor_count());
  movie.deflection_um.resize(static_cast<std::size_t>(movie.frame_count) * n);
  const double amplitude =
      0.5 * std::min(info.layout.deflection_max_um, -info.layout.deflection_min_um);
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    for (std::size_t i = 0; i < n; ++i) {
      movie.deflection_um[static_cast<std::size_t>(f) * n + i] = static_cast<float>(
          amplitude * std::sin(2.0 * M_PI * (5.0 * f / rate_hz + static_cast<double>(i) / n)));
    }
  }
  return movie;
}

td::DeviceDescription find_backend(const std::string& backend) {
  for (const auto& d : td::list_usb_devices()) {
    if (td::to_string(d.backend) == backend) return d;
  }
  throw td::TransportError("no display listed through " + backend);
}

// Host submit to device play of one frame on an idle started device, timed in the guest; the
// resolution is one status round trip, measured alongside.
void latency_probe(td::Transport& t, const td::DeviceInfo& info, double rate_hz) {
  t.start(rate_hz);
  const double r0 = uptime_s();
  for (int i = 0; i < 20; ++i) t.status();
  const double rtt = (uptime_s() - r0) / 20;
  std::vector<float> zero(static_cast<std::size_t>(info.layout.contactor_count()), 0.0f);
  double worst = 0;
  double sum = 0;
  const int probes = 20;
  for (int k = 0; k < probes; ++k) {
    const auto frame = td::encode_frame(zero, static_cast<std::uint32_t>(k), true);
    const double t0 = uptime_s();
    while (!t.send_frame(frame)) t.wait(std::chrono::microseconds(100));
    while (t.status().frames_played < static_cast<std::uint64_t>(k + 1)) {
      if (uptime_s() - t0 > 1.0) throw td::TransportError("latency probe: frame not played");
    }
    const double dt = uptime_s() - t0;
    worst = std::max(worst, dt);
    sum += dt;
  }
  t.stop();
  std::printf("VM: latency_ms mean=%.3f max=%.3f status_rtt_ms=%.3f probes=%d\n",
              1e3 * sum / probes, 1e3 * worst, 1e3 * rtt, probes);
}

// Fill reports on the vendor interface's interrupt IN endpoint, read with plain libusb.
int read_fill_reports_libusb(double rate_hz) {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return -1;
  libusb_device_handle* h =
      libusb_open_device_with_vid_pid(ctx, TFW_USB_VENDOR_ID, TFW_USB_PRODUCT_ID);
  int count = -1;
  if (h != nullptr && libusb_claim_interface(h, TFW_USB_VENDOR_INTERFACE) == 0) {
    libusb_control_transfer(h, 0x41, TFW_USB_REQ_START, static_cast<std::uint16_t>(rate_hz),
                            TFW_USB_VENDOR_INTERFACE, nullptr, 0, 1000);
    count = 0;
    int good = 0;
    const double t0 = uptime_s();
    while (uptime_s() - t0 < 0.5) {
      std::uint8_t buf[TFW_FILL_BYTES];
      int n = 0;
      if (libusb_interrupt_transfer(h, TFW_USB_EP_FILL_IN, buf, sizeof buf, &n, 200) != 0) break;
      ++count;
      tfw_fill_report r{};
      if (tfw_decode_fill(buf, static_cast<std::size_t>(n), &r) == TFW_OK && r.fifo_capacity > 0 &&
          r.rate_hz == static_cast<std::uint16_t>(rate_hz)) {
        ++good;
      }
    }
    const double dt = uptime_s() - t0;
    libusb_control_transfer(h, 0x41, TFW_USB_REQ_STOP, 0, TFW_USB_VENDOR_INTERFACE, nullptr, 0,
                            1000);
    std::printf("VM: fill_reports ep=0x81 count=%d valid=%d per_s=%.0f\n", count, good, count / dt);
    libusb_release_interface(h, TFW_USB_VENDOR_INTERFACE);
  }
  if (h != nullptr) libusb_close(h);
  libusb_exit(ctx);
  return count;
}

// Fill reports as input report 2 on the HID interface, read through hidraw.
void read_fill_reports_hidraw(const std::string& path) {
  hid_device* d = hid_open_path(path.c_str());
  if (d == nullptr) return;
  int count = 0;
  int good = 0;
  const double t0 = uptime_s();
  while (uptime_s() - t0 < 0.5) {
    std::uint8_t buf[64];
    const int n = hid_read_timeout(d, buf, sizeof buf, 200);
    if (n <= 0) break;
    ++count;
    tfw_fill_report r{};
    if (buf[0] == TFW_HID_REPORT_FILL &&
        tfw_decode_fill(buf + 1, static_cast<std::size_t>(n - 1), &r) == TFW_OK) {
      ++good;
    }
  }
  std::printf("VM: fill_reports ep=0x82 count=%d valid=%d per_s=%.0f\n", count, good,
              count / (uptime_s() - t0));
  hid_close(d);
}

int play(const std::string& backend, double rate_hz, double seconds, double wait_s) {
  if (wait_for_device(wait_s).empty()) {
    std::printf("VM: error=the display did not come back\n");
    return 1;
  }
  try {
    const td::DeviceDescription dev = find_backend(backend);
    auto transport = td::open_usb_transport(dev);
    const td::DeviceInfo info = transport->info();
    const tactile::movie::TactileMovie movie = make_movie(info, rate_hz, seconds);
    std::printf("VM: playing backend=%s path=%s rate=%g frames=%d at_s=%.3f\n", backend.c_str(),
                dev.path.c_str(), rate_hz, movie.frame_count, uptime_s());
    std::fflush(stdout);
    const double cpu0 = cpu_s();
    const td::PlaybackReport r = td::play_movie(movie, *transport);
    const double cpu = cpu_s() - cpu0;
    std::printf(
        "VM: played backend=%s sent=%lld played=%lld underruns=%lld malformed=%lld "
        "overflows=%lld min_fill=%u max_fill=%u device_s=%.3f wall_s=%.3f rate_achieved=%.1f "
        "cpu_us_per_frame=%.1f\n",
        backend.c_str(), static_cast<long long>(r.frames_sent),
        static_cast<long long>(r.frames_played), static_cast<long long>(r.underruns),
        static_cast<long long>(r.malformed), static_cast<long long>(r.overflows), r.min_fifo_fill,
        r.max_fifo_fill, r.duration_s, r.wall_s, static_cast<double>(r.frames_sent) / r.wall_s,
        1e6 * cpu / static_cast<double>(r.frames_sent));
    std::fflush(stdout);
    latency_probe(*transport, info, rate_hz);
    transport.reset();
    if (backend == "libusb") {
      read_fill_reports_libusb(rate_hz);
    } else {
      read_fill_reports_hidraw(dev.path);
    }
  } catch (const std::exception& e) {
    std::printf("VM: error=%s at_s=%.3f\n", e.what(), uptime_s());
    std::fflush(stdout);
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "enumerate") return enumerate();
  if ((mode == "play" || mode == "replay") && argc == 5) {
    // A replay waits longer: the host plugs the display back in only after the first run ended.
    return play(argv[2], std::atof(argv[3]), std::atof(argv[4]), mode == "replay" ? 60 : 20);
  }
  std::fprintf(stderr,
               "usage: vm_client enumerate | (play|replay) libusb|hidapi RATE_HZ SECONDS\n");
  return 2;
}
