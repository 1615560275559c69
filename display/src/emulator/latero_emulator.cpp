// The emulated Latero controller; see latero_emulator.hpp.
#include "tactile/display/latero_emulator.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "latero/latero_udp.hpp"

namespace tactile::display {

using Clock = std::chrono::steady_clock;

std::string format_latero_counters(const LateroEmulatorCounters& c) {
  std::string out =
      fmt::format("datagrams   {} received: {} FULL (frames played), {} IO, {} RAW, {} malformed\n",
                  c.datagrams, c.full_requests, c.io_requests, c.raw_requests, c.malformed);
  out += fmt::format("replies     {} sent, {} left out on purpose\n", c.replies_sent,
                     c.replies_dropped);
  out += fmt::format("high volt.  switched on {} times\n", c.high_voltage_enables);
  if (!c.malformed_by_reason.empty()) {
    out += "malformed  ";
    for (const auto& [reason, n] : c.malformed_by_reason) out += fmt::format(" {} {},", reason, n);
    out.back() = '\n';
  }
  return out;
}

LateroDeviceModel::LateroDeviceModel(const LateroEmulatorOptions& options)
    : options_(options), dio_in_(options.dio_in) {
  blades_.fill(0x80);
}

void LateroDeviceModel::set_buttons(bool button0_held, bool button1_held) {
  dio_in_ = options_.dio_in;
  if (button0_held) dio_in_ &= static_cast<std::uint16_t>(~kLateroButton0Mask);
  if (button1_held) dio_in_ &= static_cast<std::uint16_t>(~kLateroButton1Mask);
}

std::optional<std::vector<std::uint8_t>> LateroDeviceModel::handle(
    std::span<const std::uint8_t> datagram, Clock::time_point now) {
  ++counters_.datagrams;
  const auto decoded = decode_latero_request(datagram);
  if (!decoded.packet) {
    ++counters_.malformed;
    ++counters_.malformed_by_reason[latero_error_name(decoded.error)];
    return std::nullopt;
  }
  const LateroRequest& q = *decoded.packet;
  LateroReply reply;
  reply.sequence = q.sequence;  // echoed; OpenLatero's clients ignore it
  if (q.type == LateroPacketType::raw) {
    ++counters_.raw_requests;
    const std::uint32_t key =
        (std::uint32_t{static_cast<std::uint8_t>(q.raw_command & 0xF0)} << 16) | q.raw_address;
    if ((q.raw_command & 0x0F) == kLateroRawWrite) registers_[key] = q.raw_data;
    reply.type = LateroPacketType::raw_reply;
    reply.raw_command = q.raw_command;
    reply.raw_address = q.raw_address;
    const auto it = registers_.find(key);
    reply.raw_data = it == registers_.end() ? 0 : it->second;
  } else {
    const bool was_on = last_drive_ && now - *last_drive_ <= options_.high_voltage_timeout;
    if (!was_on) ++counters_.high_voltage_enables;
    last_drive_ = now;
    if (q.type == LateroPacketType::full) {
      ++counters_.full_requests;
      blades_ = q.blade;
    } else {
      ++counters_.io_requests;
    }
    LateroControllerStatus s;
    s.fpga_version = options_.fpga_version;
    s.fpga_revision = options_.fpga_revision;
    s.high_voltage_active = true;  // a FULL or IO request has just switched it on
    reply.type = LateroPacketType::full_reply_page0;
    reply.controller_status = encode_controller_status(s);
    reply.io_status = options_.io_status;
    reply.dio_in = dio_in_;
  }
  ++replies_due_;
  if (options_.drop_every_nth_reply > 0 && replies_due_ % options_.drop_every_nth_reply == 0) {
    ++counters_.replies_dropped;
    return std::nullopt;
  }
  ++counters_.replies_sent;
  return encode_latero_reply(reply);
}

LateroEmulator::LateroEmulator(const LateroEmulatorOptions& options)
    : model_(options), bind_address_(options.bind_address) {
  std::string why;
  socket_ = detail::open_udp_socket(options.bind_address, options.port, detail::UdpRole::bind, true,
                                    0, why);
  if (socket_ < 0) {
    throw std::runtime_error(fmt::format("emulated Latero: cannot bind {} port {} ({})",
                                         options.bind_address, options.port, why));
  }
  sockaddr_storage bound{};
  socklen_t len = sizeof bound;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&bound), &len);
  port_ =
      ntohs(bound.ss_family == AF_INET6 ? reinterpret_cast<const sockaddr_in6*>(&bound)->sin6_port
                                        : reinterpret_cast<const sockaddr_in*>(&bound)->sin_port);
}

LateroEmulator::~LateroEmulator() {
  if (socket_ >= 0) ::close(socket_);
}

std::string LateroEmulator::address() const {
  if (bind_address_.find(':') != std::string::npos) {
    return fmt::format("[{}]:{}", bind_address_, port_);
  }
  return fmt::format("{}:{}", bind_address_, port_);
}

void LateroEmulator::serve(Clock::time_point until, int stop_fd) {
  // One byte more than a datagram may have, so that an oversized one is seen as such.
  std::array<std::uint8_t, kLateroDatagramBytes + 1> buffer{};
  while (!stop_.load()) {
    const auto now = Clock::now();
    if (now >= until) return;
    // Wake at least every 50 ms to notice request_stop().
    const auto left = std::min<Clock::duration>(until - now, std::chrono::milliseconds(50));
    const timespec ts = detail::to_timespec(left);
    std::array<pollfd, 2> fds{pollfd{socket_, POLLIN, 0}, pollfd{stop_fd, POLLIN, 0}};
    const int ready = ::ppoll(fds.data(), stop_fd >= 0 ? 2 : 1, &ts, nullptr);
    if (ready < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(
          fmt::format("emulated Latero at {}: poll failed ({})", address(), std::strerror(errno)));
    }
    if (stop_fd >= 0 && (fds[1].revents & POLLIN) != 0) return;
    if ((fds[0].revents & POLLIN) == 0) continue;
    for (;;) {
      sockaddr_storage from{};
      socklen_t from_len = sizeof from;
      // MSG_TRUNC: the length returned is the datagram's, even when it did not fit.
      const ssize_t n = ::recvfrom(socket_, buffer.data(), buffer.size(), MSG_DONTWAIT | MSG_TRUNC,
                                   reinterpret_cast<sockaddr*>(&from), &from_len);
      if (n < 0) break;
      const std::size_t size = std::min(static_cast<std::size_t>(n), buffer.size());
      std::optional<std::vector<std::uint8_t>> reply;
      {
        const std::lock_guard lock(mutex_);
        reply = model_.handle({buffer.data(), size}, Clock::now());
      }
      if (reply) {
        // A reply that cannot be sent is lost as on a real network; the client counts it.
        (void)::sendto(socket_, reply->data(), reply->size(), 0,
                       reinterpret_cast<const sockaddr*>(&from), from_len);
      }
    }
  }
}

LateroEmulatorCounters LateroEmulator::counters() const {
  const std::lock_guard lock(mutex_);
  return model_.counters();
}

std::array<std::uint8_t, kLateroBlades> LateroEmulator::blades() const {
  const std::lock_guard lock(mutex_);
  return model_.blades();
}

}  // namespace tactile::display
