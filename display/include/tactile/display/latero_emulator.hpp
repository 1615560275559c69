#pragma once
// An emulated Latero controller: answers the OpenLatero protocol (latero_protocol.hpp) on UDP
// as the controller does, so that this project's transport and third-party Latero software can
// be run without the device. Malformed datagrams are counted by reason and dropped, never
// played. The model (LateroDeviceModel) is separate from the socket (LateroEmulator) so that
// tests can feed it datagrams directly.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tactile/display/latero_protocol.hpp"

namespace tactile::display {

struct LateroEmulatorOptions {
  // Loopback unless told otherwise: an emulator should not answer the whole network.
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = kLateroDefaultPort;  // 0: any free port (see LateroEmulator::port())
  // 0: answer every request; N: leave out the N-th, 2N-th, ... reply (to test loss).
  std::uint32_t drop_every_nth_reply = 0;
  int fpga_version = 1;
  int fpga_revision = 0;
  // IO board status word; 0 means no IO board (OpenLatero's TactileDisplay then refuses the
  // device, so the default reports one: FPGA 1.0).
  std::uint16_t io_status = 0x0100;
  // Digital inputs, active-low: 0xFFFF = both buttons released.
  std::uint16_t dio_in = 0xFFFF;
  // The controller switches high voltage on when a FULL or IO request arrives and (as this
  // emulator assumes) off again after this long without one.
  std::chrono::milliseconds high_voltage_timeout{100};
};

struct LateroEmulatorCounters {
  std::uint64_t datagrams = 0;      // everything received, well-formed or not
  std::uint64_t full_requests = 0;  // frames played
  std::uint64_t io_requests = 0;
  std::uint64_t raw_requests = 0;
  std::uint64_t replies_sent = 0;
  std::uint64_t replies_dropped = 0;  // left out on purpose (drop_every_nth_reply)
  std::uint64_t malformed = 0;
  std::map<std::string, std::uint64_t> malformed_by_reason;  // latero_error_name -> count
  std::uint64_t high_voltage_enables = 0;                    // off -> active transitions
};

// Several lines for people: requests by type, replies, malformed by reason.
std::string format_latero_counters(const LateroEmulatorCounters& counters);

class LateroDeviceModel {
 public:
  explicit LateroDeviceModel(const LateroEmulatorOptions& options = {});
  // Handles one datagram received at `now`; returns the reply to send (none for a malformed
  // datagram or a reply left out on purpose).
  std::optional<std::vector<std::uint8_t>> handle(std::span<const std::uint8_t> datagram,
                                                  std::chrono::steady_clock::time_point now);
  const LateroEmulatorCounters& counters() const { return counters_; }
  // Blade bytes as last played (row-major); all at 0x80 before the first FULL request, where
  // OpenLatero's client parks them.
  const std::array<std::uint8_t, kLateroBlades>& blades() const { return blades_; }
  // Hold (true) or release a button; shown active-low in dio_in.
  void set_buttons(bool button0_held, bool button1_held);

 private:
  LateroEmulatorOptions options_;
  LateroEmulatorCounters counters_;
  std::array<std::uint8_t, kLateroBlades> blades_{};
  std::uint16_t dio_in_ = 0xFFFF;
  std::map<std::uint32_t, std::uint16_t> registers_;  // (command target << 16 | address)
  std::optional<std::chrono::steady_clock::time_point> last_drive_;
  std::uint64_t replies_due_ = 0;
};

// The model on a UDP socket.
class LateroEmulator {
 public:
  // Binds; throws std::runtime_error naming the address when it cannot.
  explicit LateroEmulator(const LateroEmulatorOptions& options = {});
  ~LateroEmulator();
  LateroEmulator(const LateroEmulator&) = delete;
  LateroEmulator& operator=(const LateroEmulator&) = delete;

  std::uint16_t port() const { return port_; }
  std::string address() const;  // "127.0.0.1:8900"
  // Answers datagrams until `until`, until request_stop(), or until `stop_fd` (e.g. a
  // signalfd; -1 for none) becomes readable.
  void serve(std::chrono::steady_clock::time_point until, int stop_fd = -1);
  void request_stop() { stop_.store(true); }
  // Safe to call while another thread serves.
  LateroEmulatorCounters counters() const;
  std::array<std::uint8_t, kLateroBlades> blades() const;

 private:
  LateroDeviceModel model_;
  mutable std::mutex mutex_;  // guards model_ between serve() and the accessors
  std::atomic<bool> stop_{false};
  std::string bind_address_;
  int socket_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace tactile::display
