// The emulated device: firmware core + clock + output recorder behind Transport.
#include "tactile/display/emulated_device.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "tactile/display/control_codec.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/movie/limits.hpp"
#include "tactile_fw/control.h"
#include "tactile_fw/device.h"

namespace tactile::display {

namespace {

std::uint16_t integer_rate(double rate_hz, const char* what) {
  movie::require_playable_rate(rate_hz, what);
  return static_cast<std::uint16_t>(std::round(rate_hz));
}

tfw_config make_config(const EmulatedDeviceOptions& o) {
  const movie::Layout& l = o.layout;
  validate_movie(movie::TactileMovie{l, l.max_rate_hz, 0, {}, {}});
  tfw_config c{};
  c.rows = static_cast<std::uint16_t>(l.rows);
  c.cols = static_cast<std::uint16_t>(l.cols);
  c.pitch_x_nm = static_cast<std::uint32_t>(std::lround(l.pitch_x_mm * 1e6));
  c.pitch_y_nm = static_cast<std::uint32_t>(std::lround(l.pitch_y_mm * 1e6));
  c.contactor_width_nm = static_cast<std::uint32_t>(std::lround(l.contactor_width_mm * 1e6));
  c.contactor_height_nm = static_cast<std::uint32_t>(std::lround(l.contactor_height_mm * 1e6));
  c.axis = l.axis == movie::DeflectionAxis::x ? 0 : 1;
  c.deflection_min = to_wire_units(static_cast<float>(l.deflection_min_um));
  c.deflection_max = to_wire_units(static_cast<float>(l.deflection_max_um));
  c.max_slew_per_s =
      static_cast<std::uint32_t>(std::lround(o.max_slew_um_per_s * TFW_UNITS_PER_UM));
  c.max_rate_hz = integer_rate(l.max_rate_hz, "layout max_rate_hz");
  c.rate_hz = c.max_rate_hz;
  c.watchdog_timeout_ms = static_cast<std::uint16_t>(std::lround(o.watchdog_timeout_s * 1000));
  const tfw_config_result r = tfw_config_check(&c);
  if (r != TFW_CONFIG_OK) {
    throw std::invalid_argument(fmt::format("emulated device options rejected by the firmware: {}",
                                            tfw_config_result_name(r)));
  }
  return c;
}

}  // namespace

struct EmulatedDevice::Impl {
  EmulatedDeviceOptions options;
  mutable std::mutex mutex;
  tfw_device device{};
  double tick_period_s = 0;
  double now_s = 0;        // device time (simulated clock)
  double next_tick_s = 0;  // when the next tick is due
  std::vector<float> recorded;
  std::vector<DeviceTick> recorded_states;
  std::int64_t recorded_ticks = 0;
  double recording_rate_hz = 0;
  // Real-time clock: a thread ticks the firmware like the device's hardware timer would.
  std::thread ticker;
  std::atomic<bool> quit{false};
  std::chrono::steady_clock::time_point epoch = std::chrono::steady_clock::now();

  void set_rate(double rate_hz) {
    tick_period_s = 1.0 / rate_hz;
    recording_rate_hz = rate_hz;
  }

  // Runs every tick due up to device time `t_s`. Caller holds the mutex.
  void run_until(double t_s) {
    now_s = t_s;
    const auto n = tfw_device_contactor_count(&device);
    // The tolerance absorbs nanosecond rounding of wait() durations, so waiting one period
    // runs exactly one tick.
    while (next_tick_s <= now_s + 2e-9) {
      tfw_device_tick(&device);
      next_tick_s += tick_period_s;
      if (options.record_outputs) {
        const std::int16_t* out = tfw_device_outputs(&device);
        for (std::uint16_t i = 0; i < n; ++i) recorded.push_back(from_wire_units(out[i]));
        ++recorded_ticks;
        const tfw_status& c = device.counters;
        recorded_states.push_back({c.clamped_samples, c.slew_limited_samples, c.underruns,
                                   c.watchdog_trips, tfw_fifo_count(&device.fifo),
                                   device.state == TFW_STATE_STREAMING,
                                   device.state != TFW_STATE_STOPPED});
      }
    }
  }

  double real_now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch).count();
  }

  void ticker_loop() {
    while (!quit.load()) {
      double due;
      {
        std::lock_guard lock(mutex);
        run_until(real_now_s());
        due = next_tick_s;
      }
      std::this_thread::sleep_until(epoch + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                std::chrono::duration<double>(due)));
    }
  }
};

EmulatedDevice::EmulatedDevice(const EmulatedDeviceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  const tfw_config config = make_config(options);
  tfw_device_init(&impl_->device, &config, nullptr);
  impl_->set_rate(config.rate_hz);
  impl_->next_tick_s = impl_->tick_period_s;
  if (options.clock == EmulatedClock::real_time) {
    impl_->ticker = std::thread([this] { impl_->ticker_loop(); });
  }
}

EmulatedDevice::~EmulatedDevice() {
  impl_->quit.store(true);
  if (impl_->ticker.joinable()) impl_->ticker.join();
}

DeviceInfo EmulatedDevice::info() {
  // Through the same reply bytes a USB device sends, so the host decoding is exercised too.
  std::uint8_t reply[TFW_INFO_BYTES];
  {
    std::lock_guard lock(impl_->mutex);
    tfw_encode_info(&impl_->device, reply, sizeof reply);
  }
  return decode_device_info(reply, Backend::emulated,
                            "emulated " + impl_->options.layout.name + " display",
                            impl_->options.serial, impl_->options.layout.name);
}

void EmulatedDevice::start(double rate_hz) {
  const std::uint16_t rate = integer_rate(rate_hz, "playout rate");
  std::lock_guard lock(impl_->mutex);
  if (tfw_device_start(&impl_->device, rate) != TFW_CONFIG_OK) {
    throw TransportError(fmt::format("emulated device refused to start at {} Hz (maximum {} Hz)",
                                     rate, impl_->device.config.max_rate_hz));
  }
  impl_->set_rate(rate);
  impl_->next_tick_s = impl_->now_s + impl_->tick_period_s;
  impl_->recorded.clear();
  impl_->recorded_states.clear();
  impl_->recorded_ticks = 0;
}

void EmulatedDevice::stop() {
  std::lock_guard lock(impl_->mutex);
  tfw_device_stop(&impl_->device);
}

bool EmulatedDevice::send_frame(std::span<const std::uint8_t> frame) {
  std::lock_guard lock(impl_->mutex);
  const tfw_result r = tfw_device_receive(&impl_->device, frame.data(), frame.size());
  if (r == TFW_ERR_NOT_STARTED) throw TransportError("emulated device: frame sent before start");
  return r != TFW_ERR_FIFO_FULL;
}

DeviceStatus EmulatedDevice::status() {
  std::uint8_t reply[TFW_STATUS_BYTES];
  {
    std::lock_guard lock(impl_->mutex);
    tfw_encode_status(&impl_->device, reply, sizeof reply);
  }
  return decode_device_status(reply);
}

void EmulatedDevice::wait(std::chrono::nanoseconds duration) {
  if (impl_->options.clock == EmulatedClock::real_time) {
    std::this_thread::sleep_for(duration);
    return;
  }
  std::lock_guard lock(impl_->mutex);
  impl_->run_until(impl_->now_s + std::chrono::duration<double>(duration).count());
}

float EmulatedDevice::farthest_from_rest_um() const {
  std::lock_guard lock(impl_->mutex);
  const std::int16_t* out = tfw_device_outputs(&impl_->device);
  float farthest_um = 0;
  for (std::uint16_t i = 0; i < tfw_device_contactor_count(&impl_->device); ++i) {
    farthest_um = std::max(farthest_um, std::abs(from_wire_units(out[i])));
  }
  return farthest_um;
}

double EmulatedDevice::now_s() const {
  if (impl_->options.clock == EmulatedClock::real_time) return impl_->real_now_s();
  std::lock_guard lock(impl_->mutex);
  return impl_->now_s;
}

movie::TactileMovie EmulatedDevice::recording() const {
  std::lock_guard lock(impl_->mutex);
  movie::TactileMovie m;
  m.layout = impl_->options.layout;
  m.rate_hz = impl_->recording_rate_hz;
  m.frame_count = static_cast<std::int32_t>(impl_->recorded_ticks);
  m.deflection_um = impl_->recorded;
  m.provenance = make_provenance({}, "emulated device output");
  return m;
}

std::vector<DeviceTick> EmulatedDevice::recorded_states() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->recorded_states;
}

std::int64_t EmulatedDevice::recorded_ticks() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->recorded_ticks;
}

}  // namespace tactile::display
