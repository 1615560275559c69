#pragma once
// One interface for every way of reaching a display: libusb (vendor bulk), hidapi (HID
// reports) and the in-process emulated device. The player and the viewer only see this.

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "tactile/common/names.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

// The link to the device failed (unplugged, timeout, refused request). The message names the
// device and the operation.
class TransportError : public std::runtime_error {
 public:
  explicit TransportError(const std::string& what) : std::runtime_error(what) {}
};

// How a display is reached: the in-process emulated device, USB through libusb (vendor
// interface) or hidapi (HID interface), or a Latero controller over UDP.
enum class Backend { emulated, libusb, hidapi, latero };
inline constexpr std::array<Named<Backend>, 4> kBackendNames = {{
    {Backend::emulated, "emulated"},
    {Backend::libusb, "libusb"},
    {Backend::hidapi, "hidapi"},
    {Backend::latero, "latero"},
}};
inline constexpr auto kBackends = values_of(kBackendNames);
std::string to_string(Backend backend);
// Throws std::invalid_argument naming the bad name and the accepted ones.
Backend parse_backend(std::string_view name);

// What the device reports about itself (the "device information" control request).
struct DeviceInfo {
  Backend backend = Backend::emulated;
  std::string name;
  std::string serial;
  std::string firmware_version;
  std::uint32_t protocol_version = 0;
  // Geometry; deflection_min/max_um are the firmware's clamp limits, max_rate_hz its fastest
  // playout rate.
  movie::Layout layout;
  double max_slew_um_per_s = 0;
  double watchdog_timeout_s = 0;
  std::uint32_t fifo_capacity_frames = 0;
};

// Counters since the last start() (the "status" request / IN endpoint report).
struct DeviceStatus {
  std::uint64_t frames_received = 0;  // accepted into the FIFO
  std::uint64_t frames_played = 0;
  std::uint64_t malformed = 0;                              // dropped as malformed (all reasons)
  std::map<std::string, std::uint64_t> rejected_by_reason;  // e.g. "bad_checksum" -> 2
  std::uint64_t overflows = 0;  // well-formed frames refused for lack of room
  std::uint64_t underruns = 0;  // playout ticks with an empty FIFO while streaming
  std::uint64_t sequence_gaps = 0;
  std::uint64_t clamped_samples = 0;
  std::uint64_t slew_limited_samples = 0;
  std::uint64_t watchdog_trips = 0;
  std::uint64_t ticks = 0;
  std::uint32_t last_sequence_played = 0;
  std::uint32_t fifo_fill = 0;
  std::uint32_t fifo_capacity = 0;
  bool started = false;
  bool streaming = false;
  double rate_hz = 0;
};

class Transport {
 public:
  // A transport owns its link to one device: copies would share it, so no transport copies.
  Transport() = default;
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;
  virtual ~Transport() = default;
  virtual DeviceInfo info() = 0;
  // Starts a stream at `rate_hz` (resets counters and sequence tracking, empties the FIFO).
  virtual void start(double rate_hz) = 0;
  // Stops: the device drops queued frames and ramps to neutral.
  virtual void stop() = 0;
  // Delivers one encoded frame. Returns false when the device has no room now (the caller
  // waits and resends the same frame). A malformed frame is delivered and counted by the
  // device, not refused here: the device is the judge.
  virtual bool send_frame(std::span<const std::uint8_t> frame) = 0;
  virtual DeviceStatus status() = 0;
  // Lets device time pass: hardware transports sleep; an emulated device on a simulated
  // clock advances that clock instead, so a minute of playback takes milliseconds.
  virtual void wait(std::chrono::nanoseconds duration) = 0;
};

}  // namespace tactile::display
