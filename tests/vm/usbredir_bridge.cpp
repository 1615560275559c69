#include "usbredir_bridge.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>
#include <usbredirparser.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "device_config.h"  // tests/firmware/target: the STReSS-like test device
#include "tactile_fw/usb.h"

namespace tactile::vm {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint8_t kDescriptorRequest = 6;  // GET_DESCRIPTOR
// Offset of bInterval of EP 0x82 in the configuration descriptor (usb_descriptors.c layout:
// configuration 9, interface 9, two endpoints 7 + 7, interface 9, HID 9, EP 0x82 7).
constexpr std::size_t kHidInIntervalOffset = 56;

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// usbredir numbers endpoints 0..15 OUT and 16..31 IN.
int ep_index(std::uint8_t ep) {
  return ((ep & 0x80) >> 3) | (ep & 0x0F);
}

// One power cycle of the display: firmware state plus the device controller it drives.
class Device {
 public:
  Device(const BridgeOptions& options) : defect_(options.defect_hid_interval) {
    tfw_config config = tfw_test_stress_config();
    config.rows = options.rows;
    config.cols = options.cols;
    if (tfw_device_init(&dev_, &config, nullptr) != TFW_CONFIG_OK) {
      throw std::logic_error("bridge: bad device configuration");
    }
    speed_ = options.high_speed ? TFW_USB_HIGH_SPEED : TFW_USB_FULL_SPEED;
    serial_ = options.serial;
    bus_reset();
  }
  Device(const Device&) = delete;  // the device controller points at this object
  Device& operator=(const Device&) = delete;

  void bus_reset() {
    const tfw_usb_dcd dcd{this, &Device::dcd_write, &Device::dcd_stall, &Device::dcd_ready};
    tfw_usb_init(&usb_, &dev_, &dcd, speed_, serial_.c_str());
    ready_.fill(true);
  }

  // A SETUP packet with its OUT data: false when the firmware stalled it, else true with the
  // IN data stage (if any) in `reply`.
  bool control(const std::uint8_t setup[8], const std::uint8_t* data, std::uint16_t len,
               std::vector<std::uint8_t>& reply) {
    ep0_.clear();
    stalled_ = false;
    tfw_usb_setup(&usb_, setup, data, len);
    if (stalled_) return false;
    reply = ep0_;
    const bool config_descriptor = setup[0] == 0x80 && setup[1] == kDescriptorRequest &&
                                   setup[3] == TFW_USB_DESC_CONFIGURATION;
    if (defect_ && config_descriptor && reply.size() > kHidInIntervalOffset) {
      reply[kHidInIntervalOffset] = 0;
    }
    return true;
  }

  // The configuration descriptor as the firmware has it (no defect): what the bridge tells
  // QEMU about endpoints, so that a defect reaches only the guest kernel's parser.
  std::vector<std::uint8_t> configuration() {
    const std::uint8_t* d = nullptr;
    const std::uint16_t n = tfw_usb_descriptor(&usb_, TFW_USB_DESC_CONFIGURATION, 0, &d);
    return {d, d + n};
  }

  bool out_ready(std::uint8_t ep) const { return ready_[ep & 3]; }
  void bulk_out(const std::uint8_t* p, std::uint16_t n) { tfw_usb_bulk_out(&usb_, p, n); }
  void hid_out(const std::uint8_t* p, std::uint16_t n) { tfw_usb_hid_out(&usb_, p, n); }
  std::uint16_t bulk_packet() const {
    return speed_ == TFW_USB_HIGH_SPEED ? TFW_USB_BULK_PACKET_HS : TFW_USB_BULK_PACKET_FS;
  }
  void tick() { tfw_usb_tick(&usb_); }
  bool configured() const { return usb_.configured != 0; }
  std::uint8_t configuration_value() const { return usb_.configured; }
  double rate_hz() const { return dev_.config.rate_hz; }
  bool high_speed() const { return speed_ == TFW_USB_HIGH_SPEED; }
  tfw_status status() const {
    tfw_status s{};
    tfw_device_status(&dev_, &s);
    return s;
  }

  // IN data the firmware offered during the last tick, by endpoint.
  std::vector<std::pair<std::uint8_t, std::vector<std::uint8_t>>> take_in() {
    auto out = std::move(in_);
    in_.clear();
    return out;
  }

 private:
  static int dcd_write(void* context, std::uint8_t ep, const std::uint8_t* data,
                       std::uint16_t len) {
    auto* self = static_cast<Device*>(context);
    if (ep == 0x80) {
      self->ep0_.assign(data, data + len);
    } else {
      self->in_.emplace_back(ep, std::vector<std::uint8_t>(data, data + len));
    }
    return 1;
  }
  static void dcd_stall(void* context, std::uint8_t) {
    static_cast<Device*>(context)->stalled_ = true;
  }
  static void dcd_ready(void* context, std::uint8_t ep, int ready) {
    static_cast<Device*>(context)->ready_[ep & 3] = ready != 0;
  }

  bool defect_;
  tfw_usb_speed speed_ = TFW_USB_FULL_SPEED;
  std::string serial_;
  tfw_device dev_{};
  tfw_usb usb_{};
  std::array<bool, 4> ready_{};
  std::vector<std::uint8_t> ep0_;
  bool stalled_ = false;
  std::vector<std::pair<std::uint8_t, std::vector<std::uint8_t>>> in_;
};

struct PendingOut {
  std::uint64_t id = 0;
  std::uint8_t ep = 0;
  std::vector<std::uint8_t> data;
  bool waited = false;
};

}  // namespace

struct UsbredirBridge::Impl {
  BridgeOptions options;
  int listen_fd = -1;
  int wake[2] = {-1, -1};
  std::thread thread;
  std::atomic<bool> stopping{false};
  mutable std::mutex mu;
  BridgeStats shared;  // under mu

  // Thread-only state of the current connection.
  BridgeStats local;
  int fd = -1;
  bool eof = false;
  usbredirparser* parser = nullptr;
  std::unique_ptr<Device> device;
  std::deque<PendingOut> pending[3];  // by OUT endpoint number (1 bulk, 2 HID)
  std::array<bool, 32> receiving{};
  Clock::time_point connected_at;
  Clock::time_point next_tick;
  std::uint64_t next_id = 1;
  std::deque<std::uint32_t> arrival_ticks;  // device tick at which each queued frame arrived
  std::uint32_t last_received = 0;
  double queue_ticks_sum = 0;
  bool stream_filled = false;
  std::uint32_t last_ticks = 0;

  void run();
  void accept_connection();
  void end_connection();
  void run_ticks();
  void serve_pending();
  void track_arrivals();
  void publish();

  static Impl* self(void* priv) { return static_cast<Impl*>(priv); }
  static void log(void*, int level, const char* msg) {
    if (level <= usbredirparser_warning) std::fprintf(stderr, "usbredir bridge: %s\n", msg);
  }
  static int read_cb(void* priv, std::uint8_t* data, int count);
  static int write_cb(void* priv, std::uint8_t* data, int count);
  static void hello(void* priv, usb_redir_hello_header*);
  static void reset(void* priv);
  static void set_configuration(void* priv, std::uint64_t id,
                                usb_redir_set_configuration_header* h);
  static void get_configuration(void* priv, std::uint64_t id);
  static void set_alt_setting(void* priv, std::uint64_t id, usb_redir_set_alt_setting_header* h);
  static void get_alt_setting(void* priv, std::uint64_t id, usb_redir_get_alt_setting_header* h);
  static void start_interrupt(void* priv, std::uint64_t id,
                              usb_redir_start_interrupt_receiving_header* h);
  static void stop_interrupt(void* priv, std::uint64_t id,
                             usb_redir_stop_interrupt_receiving_header* h);
  static void start_iso(void* priv, std::uint64_t id, usb_redir_start_iso_stream_header* h);
  static void start_bulk_receiving(void* priv, std::uint64_t id,
                                   usb_redir_start_bulk_receiving_header* h);
  static void cancel(void* priv, std::uint64_t id);
  static void control_packet(void* priv, std::uint64_t id, usb_redir_control_packet_header* h,
                             std::uint8_t* data, int len);
  static void bulk_packet(void* priv, std::uint64_t id, usb_redir_bulk_packet_header* h,
                          std::uint8_t* data, int len);
  static void interrupt_packet(void* priv, std::uint64_t id, usb_redir_interrupt_packet_header* h,
                               std::uint8_t* data, int len);
};

UsbredirBridge::UsbredirBridge(BridgeOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (impl_->options.socket_path.size() >= sizeof addr.sun_path) {
    throw std::runtime_error("bridge: socket path too long: " + impl_->options.socket_path);
  }
  std::strcpy(addr.sun_path, impl_->options.socket_path.c_str());
  ::unlink(addr.sun_path);
  impl_->listen_fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (impl_->listen_fd < 0 ||
      ::bind(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(impl_->listen_fd, 2) != 0 || ::pipe2(impl_->wake, O_CLOEXEC | O_NONBLOCK) != 0) {
    const std::string why = std::strerror(errno);
    if (impl_->listen_fd >= 0) ::close(impl_->listen_fd);
    throw std::runtime_error("bridge: cannot listen on " + impl_->options.socket_path + ": " + why);
  }
  impl_->thread = std::thread([this] { impl_->run(); });
}

UsbredirBridge::~UsbredirBridge() {
  impl_->stopping = true;
  const char c = 0;
  if (::write(impl_->wake[1], &c, 1) < 0) {
    // The pipe is ours and empty; the thread also checks `stopping` on every wake-up.
  }
  impl_->thread.join();
  impl_->end_connection();
  ::close(impl_->listen_fd);
  ::close(impl_->wake[0]);
  ::close(impl_->wake[1]);
  ::unlink(impl_->options.socket_path.c_str());
}

BridgeStats UsbredirBridge::stats() const {
  std::lock_guard lock(impl_->mu);
  return impl_->shared;
}

void UsbredirBridge::Impl::run() {
  while (!stopping) {
    std::vector<pollfd> fds{{wake[0], POLLIN, 0}};
    if (fd < 0) {
      fds.push_back({listen_fd, POLLIN, 0});
    } else {
      const short events =
          POLLIN | (usbredirparser_has_data_to_write(parser) > 0 ? POLLOUT : short{0});
      fds.push_back({fd, events, 0});
    }
    timespec timeout{0, 20'000'000};
    if (device != nullptr) {
      const auto left = std::max(Clock::duration::zero(), next_tick - Clock::now());
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
      timeout = {static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
    }
    if (::ppoll(fds.data(), fds.size(), &timeout, nullptr) < 0 && errno != EINTR) break;
    if (fd < 0 && (fds[1].revents & POLLIN)) accept_connection();
    if (fd >= 0 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR))) {
      const int rc = usbredirparser_do_read(parser);
      if (rc == usbredirparser_read_io_error || eof) {
        end_connection();
        publish();
        continue;
      }
    }
    if (device != nullptr) {
      run_ticks();
      serve_pending();
    }
    if (parser != nullptr && usbredirparser_has_data_to_write(parser) > 0 &&
        usbredirparser_do_write(parser) == usbredirparser_write_io_error) {
      end_connection();
    }
    publish();
  }
}

void UsbredirBridge::Impl::accept_connection() {
  fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
  if (fd < 0) return;
  eof = false;
  device = std::make_unique<Device>(options);
  receiving.fill(false);
  arrival_ticks.clear();
  last_received = 0;
  last_ticks = 0;
  stream_filled = false;
  local.underruns_at_start = 0;  // per connection: each plug-in is a new device
  local.underruns_steady = 0;
  local.max_tick_late_ms = 0;
  local.underrun_ticks.clear();
  connected_at = Clock::now();
  next_tick = connected_at;
  ++local.connections;
  local.connected = true;
  local.configured = false;
  parser = usbredirparser_create();
  parser->priv = this;
  parser->log_func = &Impl::log;
  parser->read_func = &Impl::read_cb;
  parser->write_func = &Impl::write_cb;
  parser->hello_func = &Impl::hello;
  parser->reset_func = &Impl::reset;
  parser->set_configuration_func = &Impl::set_configuration;
  parser->get_configuration_func = &Impl::get_configuration;
  parser->set_alt_setting_func = &Impl::set_alt_setting;
  parser->get_alt_setting_func = &Impl::get_alt_setting;
  parser->start_interrupt_receiving_func = &Impl::start_interrupt;
  parser->stop_interrupt_receiving_func = &Impl::stop_interrupt;
  parser->start_iso_stream_func = &Impl::start_iso;
  parser->start_bulk_receiving_func = &Impl::start_bulk_receiving;
  parser->cancel_data_packet_func = &Impl::cancel;
  parser->control_packet_func = &Impl::control_packet;
  parser->bulk_packet_func = &Impl::bulk_packet;
  parser->interrupt_packet_func = &Impl::interrupt_packet;
  std::uint32_t caps[USB_REDIR_CAPS_SIZE] = {0};
  usbredirparser_caps_set_cap(caps, usb_redir_cap_connect_device_version);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_ep_info_max_packet_size);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_64bits_ids);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_32bits_bulk_length);
  usbredirparser_init(parser, "tactile-movies bridge", caps, USB_REDIR_CAPS_SIZE,
                      usbredirparser_fl_usb_host);
}

void UsbredirBridge::Impl::end_connection() {
  if (parser != nullptr) usbredirparser_destroy(parser);
  parser = nullptr;
  if (fd >= 0) ::close(fd);
  fd = -1;
  device.reset();
  for (auto& q : pending) q.clear();
  local.connected = false;
  local.configured = false;
}

void UsbredirBridge::Impl::run_ticks() {
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / device->rate_hz()));
  const auto now = Clock::now();
  if (device->status().state == TFW_STATE_STREAMING && now > next_tick) {
    const double late_ms = std::chrono::duration<double, std::milli>(now - next_tick).count();
    local.max_tick_late_ms = std::max(local.max_tick_late_ms, late_ms);
  }
  int ticks = 0;
  while (next_tick <= now && ticks < 100) {
    const tfw_status before = device->status();
    const std::uint32_t played_before = before.frames_played;
    device->tick();
    const tfw_status s = device->status();
    if (before.ticks < last_ticks) stream_filled = false;  // a start reset the counters
    last_ticks = s.ticks;
    if (s.fifo_fill >= s.fifo_capacity / 2) stream_filled = true;
    if (s.underruns > before.underruns) {
      // The start is the first FIFO's worth of frames, and only until the FIFO first filled:
      // a link too slow ever to fill it is counted as steady state.
      const bool start = !stream_filled && s.frames_played <= s.fifo_capacity;
      ++(start ? local.underruns_at_start : local.underruns_steady);
      if (s.underruns <= 10) {
        local.underrun_ticks +=
            std::to_string(s.ticks) + "@" + std::to_string(s.frames_played) + " ";
      }
    }
    if (s.frames_played > played_before && !arrival_ticks.empty()) {
      queue_ticks_sum += static_cast<double>(s.ticks - arrival_ticks.front());
      arrival_ticks.pop_front();
      ++local.queue_samples;
    }
    for (auto& [ep, data] : device->take_in()) {
      if (!receiving[static_cast<std::size_t>(ep_index(ep))]) continue;
      usb_redir_interrupt_packet_header h{ep, usb_redir_success,
                                          static_cast<std::uint16_t>(data.size())};
      usbredirparser_send_interrupt_packet(parser, next_id++, &h, data.data(),
                                           static_cast<int>(data.size()));
      ++local.fill_reports_sent;
    }
    next_tick += period;
    ++ticks;
  }
  // A host that fell far behind resumes from now rather than replaying a burst of ticks.
  if (ticks == 100) next_tick = now + period;
  track_arrivals();
}

// Keeps arrival_ticks in step with the FIFO: frames just accepted are appended, frames dropped
// by a stop or start are forgotten.
void UsbredirBridge::Impl::track_arrivals() {
  const tfw_status s = device->status();
  if (s.frames_received < last_received) last_received = 0;  // a start reset the counters
  for (; last_received < s.frames_received; ++last_received) arrival_ticks.push_back(s.ticks);
  while (arrival_ticks.size() > s.fifo_fill) arrival_ticks.pop_front();
}

void UsbredirBridge::Impl::serve_pending() {
  for (std::uint8_t ep = 1; ep <= 2; ++ep) {
    auto& q = pending[ep];
    while (!q.empty()) {
      PendingOut& p = q.front();
      if (!device->out_ready(ep)) {
        if (!p.waited) ++local.naks;
        p.waited = true;
        break;
      }
      const auto n = static_cast<std::uint16_t>(p.data.size());
      if (ep == TFW_USB_EP_FRAMES_OUT) {
        // Full packets, then the short rest; a zero-length transfer is the zero-length packet
        // (the guest's xHCI driver queues it as a transfer of its own).
        static const std::uint8_t kNothing[1] = {0};
        const std::uint16_t max = device->bulk_packet();
        std::uint16_t at = 0;
        do {
          const auto chunk = static_cast<std::uint16_t>(std::min<int>(max, n - at));
          device->bulk_out(chunk > 0 ? p.data.data() + at : kNothing, chunk);
          at = static_cast<std::uint16_t>(at + chunk);
        } while (at < n);
        usb_redir_bulk_packet_header h{};
        h.endpoint = ep;
        h.status = usb_redir_success;
        h.length = n;
        usbredirparser_send_bulk_packet(parser, p.id, &h, nullptr, 0);
        ++local.bulk_transfers;
      } else {
        static const std::uint8_t kEmpty[1] = {0};
        device->hid_out(n > 0 ? p.data.data() : kEmpty, n);
        usb_redir_interrupt_packet_header h{ep, usb_redir_success, n};
        usbredirparser_send_interrupt_packet(parser, p.id, &h, nullptr, 0);
        ++local.hid_reports;
      }
      q.pop_front();
      track_arrivals();
    }
  }
}

void UsbredirBridge::Impl::publish() {
  if (device != nullptr) {
    const tfw_status s = device->status();
    local.frames_received = s.frames_received;
    local.frames_played = s.frames_played;
    local.underruns = s.underruns;
    local.malformed = s.malformed_total;
  }
  local.mean_queue_ticks =
      local.queue_samples > 0 ? queue_ticks_sum / static_cast<double>(local.queue_samples) : 0;
  local.bridge_cpu_s = thread_cpu_s();
  std::lock_guard lock(mu);
  shared = local;
}

int UsbredirBridge::Impl::read_cb(void* priv, std::uint8_t* data, int count) {
  Impl* me = self(priv);
  const ssize_t n = ::recv(me->fd, data, static_cast<std::size_t>(count), MSG_DONTWAIT);
  if (n > 0) return static_cast<int>(n);
  if (n == 0) {
    me->eof = true;
    return -1;
  }
  return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? 0 : -1;
}

int UsbredirBridge::Impl::write_cb(void* priv, std::uint8_t* data, int count) {
  const ssize_t n =
      ::send(self(priv)->fd, data, static_cast<std::size_t>(count), MSG_NOSIGNAL | MSG_DONTWAIT);
  if (n >= 0) return static_cast<int>(n);
  return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? 0 : -1;
}

// The peer's hello: describe the device (interfaces and endpoints from the firmware's
// configuration descriptor), then connect it.
void UsbredirBridge::Impl::hello(void* priv, usb_redir_hello_header*) {
  Impl* me = self(priv);
  const std::vector<std::uint8_t> config = me->device->configuration();
  usb_redir_interface_info_header interfaces{};
  usb_redir_ep_info_header eps{};
  std::fill(std::begin(eps.type), std::end(eps.type), std::uint8_t{usb_redir_type_invalid});
  eps.type[0] = usb_redir_type_control;
  eps.type[16] = usb_redir_type_control;
  eps.max_packet_size[0] = eps.max_packet_size[16] = TFW_USB_EP0_PACKET;
  int current_interface = 0;
  for (std::size_t at = 0; at + 2 <= config.size() && config[at] >= 2; at += config[at]) {
    const std::uint8_t* d = config.data() + at;
    if (at + d[0] > config.size()) break;
    if (d[1] == 4 && d[0] >= 9 && interfaces.interface_count < 32) {
      const std::uint32_t i = interfaces.interface_count++;
      interfaces.interface[i] = d[2];
      interfaces.interface_class[i] = d[5];
      interfaces.interface_subclass[i] = d[6];
      interfaces.interface_protocol[i] = d[7];
      current_interface = d[2];
    } else if (d[1] == 5 && d[0] >= 7) {
      const int i = ep_index(d[2]);
      eps.type[i] = d[3] & 3;
      eps.interval[i] = d[6];
      eps.interface[i] = static_cast<std::uint8_t>(current_interface);
      eps.max_packet_size[i] = static_cast<std::uint16_t>(d[4] | (d[5] << 8));
    }
  }
  usbredirparser_send_interface_info(me->parser, &interfaces);
  usbredirparser_send_ep_info(me->parser, &eps);
  usb_redir_device_connect_header connect{};
  connect.speed = me->device->high_speed() ? usb_redir_speed_high : usb_redir_speed_full;
  connect.device_class = 0;
  connect.vendor_id = TFW_USB_VENDOR_ID;
  connect.product_id = TFW_USB_PRODUCT_ID;
  connect.device_version_bcd = TFW_USB_BCD_DEVICE;
  usbredirparser_send_device_connect(me->parser, &connect);
}

void UsbredirBridge::Impl::reset(void* priv) {
  Impl* me = self(priv);
  me->device->bus_reset();
  me->local.configured = false;
}

void UsbredirBridge::Impl::set_configuration(void* priv, std::uint64_t id,
                                             usb_redir_set_configuration_header* h) {
  Impl* me = self(priv);
  const std::uint8_t setup[8] = {0x00, 9, h->configuration, 0, 0, 0, 0, 0};
  std::vector<std::uint8_t> reply;
  const bool ok = me->device->control(setup, nullptr, 0, reply);
  usb_redir_configuration_status_header status{
      ok ? std::uint8_t{usb_redir_success} : std::uint8_t{usb_redir_stall},
      me->device->configuration_value()};
  usbredirparser_send_configuration_status(me->parser, id, &status);
  if (ok && h->configuration != 0 && !me->local.configured) {
    me->local.configured = true;
    me->local.enumeration_s =
        std::chrono::duration<double>(Clock::now() - me->connected_at).count();
  }
}

void UsbredirBridge::Impl::get_configuration(void* priv, std::uint64_t id) {
  Impl* me = self(priv);
  usb_redir_configuration_status_header status{usb_redir_success,
                                               me->device->configuration_value()};
  usbredirparser_send_configuration_status(me->parser, id, &status);
}

void UsbredirBridge::Impl::set_alt_setting(void* priv, std::uint64_t id,
                                           usb_redir_set_alt_setting_header* h) {
  Impl* me = self(priv);
  const std::uint8_t setup[8] = {0x01, 11, h->alt, 0, h->interface, 0, 0, 0};
  std::vector<std::uint8_t> reply;
  const bool ok = me->device->control(setup, nullptr, 0, reply);
  usb_redir_alt_setting_status_header status{
      ok ? std::uint8_t{usb_redir_success} : std::uint8_t{usb_redir_stall}, h->interface,
      ok ? h->alt : std::uint8_t{0}};
  usbredirparser_send_alt_setting_status(me->parser, id, &status);
}

void UsbredirBridge::Impl::get_alt_setting(void* priv, std::uint64_t id,
                                           usb_redir_get_alt_setting_header* h) {
  usb_redir_alt_setting_status_header status{usb_redir_success, h->interface, 0};
  usbredirparser_send_alt_setting_status(self(priv)->parser, id, &status);
}

void UsbredirBridge::Impl::start_interrupt(void* priv, std::uint64_t id,
                                           usb_redir_start_interrupt_receiving_header* h) {
  Impl* me = self(priv);
  const bool ours = h->endpoint == TFW_USB_EP_FILL_IN || h->endpoint == TFW_USB_EP_HID_IN;
  if (ours) me->receiving[static_cast<std::size_t>(ep_index(h->endpoint))] = true;
  usb_redir_interrupt_receiving_status_header status{
      ours ? std::uint8_t{usb_redir_success} : std::uint8_t{usb_redir_inval}, h->endpoint};
  usbredirparser_send_interrupt_receiving_status(me->parser, id, &status);
}

void UsbredirBridge::Impl::stop_interrupt(void* priv, std::uint64_t id,
                                          usb_redir_stop_interrupt_receiving_header* h) {
  Impl* me = self(priv);
  me->receiving[static_cast<std::size_t>(ep_index(h->endpoint))] = false;
  usb_redir_interrupt_receiving_status_header status{usb_redir_success, h->endpoint};
  usbredirparser_send_interrupt_receiving_status(me->parser, id, &status);
}

void UsbredirBridge::Impl::start_iso(void* priv, std::uint64_t id,
                                     usb_redir_start_iso_stream_header* h) {
  usb_redir_iso_stream_status_header status{usb_redir_inval, h->endpoint};
  usbredirparser_send_iso_stream_status(self(priv)->parser, id, &status);
}

void UsbredirBridge::Impl::start_bulk_receiving(void* priv, std::uint64_t id,
                                                usb_redir_start_bulk_receiving_header* h) {
  usb_redir_bulk_receiving_status_header status{h->stream_id, h->endpoint, usb_redir_inval};
  usbredirparser_send_bulk_receiving_status(self(priv)->parser, id, &status);
}

void UsbredirBridge::Impl::cancel(void* priv, std::uint64_t id) {
  Impl* me = self(priv);
  for (std::uint8_t ep = 1; ep <= 2; ++ep) {
    auto& q = me->pending[ep];
    const auto it =
        std::find_if(q.begin(), q.end(), [id](const PendingOut& p) { return p.id == id; });
    if (it == q.end()) continue;
    q.erase(it);
    if (ep == TFW_USB_EP_FRAMES_OUT) {
      usb_redir_bulk_packet_header h{};
      h.endpoint = ep;
      h.status = usb_redir_cancelled;
      usbredirparser_send_bulk_packet(me->parser, id, &h, nullptr, 0);
    } else {
      usb_redir_interrupt_packet_header h{ep, usb_redir_cancelled, 0};
      usbredirparser_send_interrupt_packet(me->parser, id, &h, nullptr, 0);
    }
  }
}

void UsbredirBridge::Impl::control_packet(void* priv, std::uint64_t id,
                                          usb_redir_control_packet_header* h, std::uint8_t* data,
                                          int len) {
  Impl* me = self(priv);
  const std::uint8_t setup[8] = {h->requesttype,
                                 h->request,
                                 static_cast<std::uint8_t>(h->value & 0xFF),
                                 static_cast<std::uint8_t>(h->value >> 8),
                                 static_cast<std::uint8_t>(h->index & 0xFF),
                                 static_cast<std::uint8_t>(h->index >> 8),
                                 static_cast<std::uint8_t>(h->length & 0xFF),
                                 static_cast<std::uint8_t>(h->length >> 8)};
  const bool in = (h->requesttype & 0x80) != 0;
  std::vector<std::uint8_t> reply;
  const bool ok = me->device->control(setup, in ? nullptr : data,
                                      in ? 0 : static_cast<std::uint16_t>(len), reply);
  if (data != nullptr) usbredirparser_free_packet_data(me->parser, data);
  ++me->local.control_transfers;
  usb_redir_control_packet_header r = *h;
  r.status = ok ? usb_redir_success : usb_redir_stall;
  if (!ok) {
    ++me->local.control_stalls;
    r.length = 0;
    usbredirparser_send_control_packet(me->parser, id, &r, nullptr, 0);
  } else if (in) {
    if (reply.size() > h->length) reply.resize(h->length);
    r.length = static_cast<std::uint16_t>(reply.size());
    usbredirparser_send_control_packet(me->parser, id, &r, reply.data(),
                                       static_cast<int>(reply.size()));
  } else {
    usbredirparser_send_control_packet(me->parser, id, &r, nullptr, 0);
  }
  // A START or STOP may have re-armed endpoints that held transfers back.
  me->serve_pending();
}

void UsbredirBridge::Impl::bulk_packet(void* priv, std::uint64_t id,
                                       usb_redir_bulk_packet_header* h, std::uint8_t* data,
                                       int len) {
  Impl* me = self(priv);
  const bool ours = h->endpoint == TFW_USB_EP_FRAMES_OUT && len >= 0 && len <= 0xFFFF;
  if (ours) me->pending[1].push_back({id, h->endpoint, {data, data + len}, false});
  if (data != nullptr) usbredirparser_free_packet_data(me->parser, data);
  if (!ours) {
    usb_redir_bulk_packet_header r = *h;
    r.status = usb_redir_inval;
    r.length = 0;
    r.length_high = 0;
    usbredirparser_send_bulk_packet(me->parser, id, &r, nullptr, 0);
    return;
  }
  me->serve_pending();
}

void UsbredirBridge::Impl::interrupt_packet(void* priv, std::uint64_t id,
                                            usb_redir_interrupt_packet_header* h,
                                            std::uint8_t* data, int len) {
  Impl* me = self(priv);
  const bool ours = h->endpoint == TFW_USB_EP_HID_OUT && len >= 0 && len <= 0xFFFF;
  if (ours) me->pending[2].push_back({id, h->endpoint, {data, data + len}, false});
  if (data != nullptr) usbredirparser_free_packet_data(me->parser, data);
  if (!ours) {
    usb_redir_interrupt_packet_header r{h->endpoint, usb_redir_inval, 0};
    usbredirparser_send_interrupt_packet(me->parser, id, &r, nullptr, 0);
    return;
  }
  me->serve_pending();
}

}  // namespace tactile::vm
