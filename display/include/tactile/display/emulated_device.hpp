#pragma once
// A display emulated in-process: the real firmware core (firmware/src) behind the Transport
// interface, ticking on a simulated clock (tests, fast rendering) or a real one (live viewing).
// Every output frame the firmware writes is recorded, so what a caller sees is exactly what
// the device would do to the skin, clamps, slew limits and watchdog included.

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tactile/display/transport.hpp"
#include "tactile/movie/limits.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

enum class EmulatedClock { simulated, real_time };

struct EmulatedDeviceOptions {
  movie::Layout layout = movie::stress_layout();
  double max_slew_um_per_s = movie::kDefaultSlewLimitUmPerS;
  double watchdog_timeout_s = 0.005;
  EmulatedClock clock = EmulatedClock::simulated;
  bool record_outputs = true;
  std::string serial = "EMU-0001";
};

// The firmware's state after one tick: its safety counters since start() and where it stands,
// so a viewer can say what the device was doing at each output frame.
struct DeviceTick {
  std::uint32_t clamped_samples = 0;
  std::uint32_t slew_limited_samples = 0;
  std::uint32_t underruns = 0;
  std::uint32_t watchdog_trips = 0;
  std::uint16_t fifo_fill = 0;
  bool streaming = false;  // playing a stream (else idle: before it, after its end or a trip)
  bool started = false;
};

class EmulatedDevice final : public Transport {
 public:
  // Throws std::invalid_argument when the options do not make a valid firmware configuration.
  explicit EmulatedDevice(const EmulatedDeviceOptions& options = {});
  ~EmulatedDevice() override;

  DeviceInfo info() override;
  void start(double rate_hz) override;
  void stop() override;
  bool send_frame(std::span<const std::uint8_t> frame) override;
  DeviceStatus status() override;
  void wait(std::chrono::nanoseconds duration) override;

  // Device time since construction (simulated or real).
  double now_s() const;
  // Where the contactors stand now, measured on the firmware's outputs: the largest distance
  // of any contactor from rest (um), 0 once a stop's ramp has ended.
  float farthest_from_rest_um() const;
  // Outputs recorded since the last start(): one frame of rows x cols deflections (um) per
  // tick, row-major, at the rate given to start().
  movie::TactileMovie recording() const;
  std::int64_t recorded_ticks() const;
  // The firmware's state after each recorded tick (same ticks as recording()).
  std::vector<DeviceTick> recorded_states() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::display
