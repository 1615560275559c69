#pragma once
// The firmware core (tfw_device + tfw_usb, unchanged) as a USB device that a QEMU virtual
// machine sees on its xHCI controller: QEMU's `usb-redir` device speaks the usbredir protocol
// (libusbredirparser) over a unix socket, and this bridge is the "USB host" end of it, the
// part that usbredirserver plays for a real device. The bridge is the device controller:
//   - control packets become SETUP packets for tfw_usb_setup (its reply, or a stall);
//   - a bulk packet on EP 0x01 is one transfer: split into max-size packets (and a short
//     rest) for tfw_usb_bulk_out; a zero-length transfer is a zero-length packet;
//   - an interrupt packet on EP 0x02 is one HID output report for tfw_usb_hid_out;
//   - OUT packets wait unanswered while the firmware NAKs their endpoint (FIFO full): the
//     guest's transfer stays pending, exactly as on a real bus;
//   - interrupt IN endpoints the guest polls (usbredir "interrupt receiving") get the fill
//     reports the firmware offers every tick.
// The playout timer runs on the host's monotonic clock in the bridge's thread.
// One device per connection: when QEMU closes the socket (device_del), the next connection
// finds a freshly powered device, as a display plugged in again would be.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

namespace tactile::vm {

struct BridgeOptions {
  std::string socket_path;  // unix socket the bridge listens on; QEMU connects to it
  bool high_speed = false;  // announce a high-speed device (default full speed)
  // Contactor grid (the STReSS-like test device otherwise): 4 x 6 makes a frame of exactly
  // one full-speed packet, so every frame ends with a zero-length packet.
  std::uint16_t rows = 10;
  std::uint16_t cols = 10;
  // A deliberate defect for the test that shows the enumeration test can fail: the
  // configuration descriptor sent to the host has bInterval 0 on the HID IN endpoint 0x82,
  // which USB 2.0 forbids for interrupt endpoints.
  bool defect_hid_interval = false;
  std::string serial = "VM0001";
};

struct BridgeStats {
  int connections = 0;
  bool connected = false;
  bool configured = false;
  // From the connection to the SET_CONFIGURATION that ended enumeration (the host's view).
  double enumeration_s = 0;
  std::uint64_t control_transfers = 0;
  std::uint64_t control_stalls = 0;
  std::uint64_t bulk_transfers = 0;     // EP 0x01
  std::uint64_t hid_reports = 0;        // EP 0x02 (interrupt OUT)
  std::uint64_t fill_reports_sent = 0;  // EP 0x81 and 0x82 together
  std::uint64_t naks = 0;               // OUT transfers that had to wait for room in the FIFO
  // The firmware's own counters at the last look.
  std::uint64_t frames_received = 0;
  std::uint64_t frames_played = 0;
  std::uint64_t underruns = 0;
  std::uint64_t malformed = 0;
  // Time a frame spends between arriving at the device and being played, device ticks
  // averaged over frames (the FIFO's queueing delay, at the device's clock).
  double mean_queue_ticks = 0;
  std::uint64_t queue_samples = 0;
  double bridge_cpu_s = 0;  // CPU time of the bridge thread
  // Underruns split by when they happened in a stream: at its start (within the first FIFO's
  // worth of frames played and before the FIFO first reached half full, while the host is
  // still filling it) or after (steady state).
  std::uint64_t underruns_at_start = 0;
  std::uint64_t underruns_steady = 0;
  // Longest the bridge's thread ran late for a tick while a stream played: more than a few
  // milliseconds means the host machine was starved by other work (per connection).
  double max_tick_late_ms = 0;
  // Where underruns happened, for the log: "tick@frames_played" of the first few.
  std::string underrun_ticks;
};

class UsbredirBridge {
 public:
  // Listens on options.socket_path and serves connections in a thread until destroyed.
  // Throws std::runtime_error when the socket cannot be made.
  explicit UsbredirBridge(BridgeOptions options);
  ~UsbredirBridge();
  UsbredirBridge(const UsbredirBridge&) = delete;
  UsbredirBridge& operator=(const UsbredirBridge&) = delete;

  BridgeStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::vm
