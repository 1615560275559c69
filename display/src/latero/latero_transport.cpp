// A Latero over UDP, paced by the host clock; see latero_transport.hpp.
#include "tactile/display/latero_transport.hpp"
#include "tactile/common/stats.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "latero/latero_udp.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile_fw/wire.h"

namespace tactile::display {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::duration_cast;
using std::chrono::microseconds;
using std::chrono::nanoseconds;

std::uint16_t parse_port(const std::string& text, const std::string& whole) {
  if (text.empty() || text.size() > 5 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw std::invalid_argument(
        fmt::format("Latero address '{}': port '{}' is not a number 1..65535", whole, text));
  }
  const int port = std::stoi(text);
  if (port < 1 || port > 65535) {
    throw std::invalid_argument(
        fmt::format("Latero address '{}': port {} is outside 1..65535", whole, port));
  }
  return static_cast<std::uint16_t>(port);
}

// Sleeps most of the way, then spins: a sleeping thread wakes 50-100 us late on a loaded
// machine, a fifth of a 750 Hz period.
constexpr nanoseconds kSpin = microseconds(200);

}  // namespace

std::string describe_malformed_replies(const LateroLinkStats& stats) {
  if (stats.malformed_replies == 0) return {};
  std::vector<std::pair<std::uint64_t, std::string>> kinds;
  if (stats.echoed_requests > 0) {
    kinds.emplace_back(stats.echoed_requests, "our own requests echoed back");
  }
  for (int e = 1; e < kLateroPacketErrorCount; ++e) {
    const auto count = stats.malformed_by_error[static_cast<std::size_t>(e)];
    if (count > 0) kinds.emplace_back(count, latero_error_words(static_cast<LateroPacketError>(e)));
  }
  std::stable_sort(kinds.begin(), kinds.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  const std::string noun = stats.malformed_replies == 1 ? "reply" : "replies";
  if (kinds.size() == 1) {
    return fmt::format("{} malformed {}: {}", stats.malformed_replies, noun, kinds[0].second);
  }
  std::string parts;
  for (const auto& [count, words] : kinds) {
    parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", count, words);
  }
  return fmt::format("{} malformed {}: {}", stats.malformed_replies, noun, parts);
}

std::string LateroAddress::text() const {
  if (host.find(':') != std::string::npos) return fmt::format("[{}]:{}", host, port);
  return fmt::format("{}:{}", host, port);
}

LateroAddress parse_latero_address(const std::string& text) {
  LateroAddress a;
  std::string port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos) {
      throw std::invalid_argument(
          fmt::format("Latero address '{}': '[' without ']' around an IPv6 address", text));
    }
    a.host = text.substr(1, close - 1);
    const std::string rest = text.substr(close + 1);
    if (!rest.empty()) {
      if (rest.front() != ':') {
        throw std::invalid_argument(
            fmt::format("Latero address '{}': expected ':PORT' after ']', got '{}'", text, rest));
      }
      port = rest.substr(1);
      a.port = parse_port(port, text);
    }
  } else if (std::count(text.begin(), text.end(), ':') > 1) {
    a.host = text;  // a bare IPv6 address, default port
  } else {
    const auto colon = text.find(':');
    a.host = text.substr(0, colon);
    if (colon != std::string::npos) a.port = parse_port(text.substr(colon + 1), text);
  }
  if (a.host.empty()) {
    throw std::invalid_argument(
        fmt::format("Latero address '{}': no host (expected HOST[:PORT])", text));
  }
  return a;
}

LateroTransport::LateroTransport(LateroAddress address, LateroTransportOptions options)
    : address_(std::move(address)), options_(std::move(options)) {
  validate_blade_mapping(options_.mapping);
  if (options_.layout.contactor_count() != kLateroBlades) {
    throw std::invalid_argument(fmt::format("layout '{}' has {} contactors; a Latero has {} blades",
                                            options_.layout.name, options_.layout.contactor_count(),
                                            kLateroBlades));
  }
  std::string why;
  // Connected: the kernel keeps datagrams from anyone else out, and an ICMP "port
  // unreachable" comes back as ECONNREFUSED instead of silence.
  socket_ = detail::open_udp_socket(address_.host, address_.port, detail::UdpRole::connect, false,
                                    SOCK_NONBLOCK, why);
  if (socket_ < 0) {
    throw TransportError(
        fmt::format("Latero at {}: cannot open a UDP socket ({})", address_.text(), why));
  }
  last_blades_.fill(centre_raw(options_.mapping));
}

LateroTransport::~LateroTransport() {
  if (streaming_) {
    try {
      stop();
    } catch (...) {
      // A destructor must not throw; the blades stay where the last frame put them.
    }
  }
  if (socket_ >= 0) ::close(socket_);
}

void LateroTransport::send_request(const LateroRequest& request) {
  LateroRequest r = request;
  // OpenLatero leaves the sequence field unmaintained; numbering it costs nothing and lets
  // replies that echo it be matched to their request.
  r.sequence = sequence_++;
  const auto bytes = encode_latero_request(r);
  const auto now = Clock::now();
  for (int attempt = 0;; ++attempt) {
    const ssize_t n = ::send(socket_, bytes.data(), bytes.size(), 0);
    if (n == static_cast<ssize_t>(bytes.size())) break;
    // A refusal reported for an earlier datagram, or a full socket buffer: try once more;
    // the link check reports a device that is really gone.
    if (n < 0 && (errno == ECONNREFUSED || errno == EAGAIN || errno == EINTR) && attempt < 2) {
      if (errno == ECONNREFUSED) refused_ = true;
      continue;
    }
    if (n < 0 && (errno == ECONNREFUSED || errno == EAGAIN)) break;  // counted as missed
    throw TransportError(fmt::format("Latero at {}: send failed ({})", address_.text(),
                                     n < 0 ? std::strerror(errno) : "short write"));
  }
  if (unanswered_since_ == Clock::time_point{}) unanswered_since_ = now;
  outstanding_.push_back({r.sequence, now});
  ++stats_.requests_sent;
}

void LateroTransport::receive_ready() {
  std::array<std::uint8_t, kLateroDatagramBytes + 1> buffer{};
  for (;;) {
    const ssize_t n = ::recv(socket_, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n < 0) {
      if (errno == ECONNREFUSED) {
        refused_ = true;
        continue;
      }
      return;  // EAGAIN: nothing more now
    }
    const std::span<const std::uint8_t> bytes{buffer.data(), static_cast<std::size_t>(n)};
    const auto decoded = decode_latero_reply(bytes);
    if (!decoded.packet) {
      ++stats_.malformed_replies;
      if (decode_latero_request(bytes).packet) {
        ++stats_.echoed_requests;
      } else {
        ++stats_.malformed_by_error[static_cast<std::size_t>(decoded.error)];
      }
      continue;
    }
    const auto now = Clock::now();
    expire(now);
    ++stats_.replies_received;
    stats_.last_reply = *decoded.packet;
    stats_.any_reply = true;
    unanswered_since_ = {};
    // The reply to the request that carried its sequence number, else (a controller that does
    // not echo it) to the oldest one waiting.
    auto it = std::find_if(outstanding_.begin(), outstanding_.end(), [&](const Outstanding& o) {
      return o.sequence == decoded.packet->sequence;
    });
    if (it == outstanding_.end() && !outstanding_.empty()) it = outstanding_.begin();
    if (it == outstanding_.end()) {
      ++stats_.late_replies;  // its request was already counted as missed
    } else {
      outstanding_.erase(it);
    }
  }
}

void LateroTransport::expire(Clock::time_point now) {
  while (!outstanding_.empty() && now - outstanding_.front().sent_at > options_.reply_timeout) {
    outstanding_.pop_front();
    ++stats_.missed_replies;
  }
}

void LateroTransport::drain(Clock::time_point until) {
  for (;;) {
    receive_ready();
    const auto now = Clock::now();
    expire(now);
    if (now >= until) return;
    const auto left = duration_cast<nanoseconds>(until - now);
    const timespec ts = detail::to_timespec(left);
    pollfd p{socket_, POLLIN, 0};
    if (::ppoll(&p, 1, &ts, nullptr) < 0 && errno != EINTR) {
      throw TransportError(
          fmt::format("Latero at {}: poll failed ({})", address_.text(), std::strerror(errno)));
    }
  }
}

void LateroTransport::check_link() {
  if (unanswered_since_ == Clock::time_point{}) return;
  const auto silent = Clock::now() - unanswered_since_;
  if (silent <= options_.link_timeout) return;
  if (stats_.malformed_replies > 0) throw nonsense_error("for");
  throw TransportError(fmt::format(
      "Latero at {}: no reply for {} ms ({} requests sent, {} replies){}; is the device on and "
      "at this address and port?",
      address_.text(), options_.link_timeout.count(), stats_.requests_sent, stats_.replies_received,
      refused_ ? "; the host answered that nothing listens on that port" : ""));
}

TransportError LateroTransport::nonsense_error(const char* for_or_within) const {
  // Something answers, but not as a Latero does: saying "no reply" would send the user
  // looking for a cable or a power switch instead of at what listens on that port.
  return TransportError(fmt::format(
      "Latero at {} answered {}, and no valid reply {} {} ms ({} requests sent); is a Latero "
      "at this address and port?",
      address_.text(), describe_malformed_replies(stats_), for_or_within,
      options_.link_timeout.count(), stats_.requests_sent));
}

LateroReply LateroTransport::probe() {
  LateroRequest r;
  r.type = LateroPacketType::io;
  r.dio_out = options_.dio_out;
  const auto deadline = Clock::now() + options_.link_timeout;
  const std::uint64_t before = stats_.replies_received;
  // Resend every 50 ms: a single lost datagram should not make a device look absent.
  while (stats_.replies_received == before && Clock::now() < deadline) {
    send_request(r);
    const auto resend = std::min(deadline, Clock::now() + std::chrono::milliseconds(50));
    while (stats_.replies_received == before && Clock::now() < resend) {
      drain(std::min(resend, Clock::now() + std::chrono::milliseconds(1)));
    }
  }
  if (stats_.replies_received == before) {
    if (stats_.malformed_replies > 0) throw nonsense_error("within");
    throw TransportError(fmt::format(
        "Latero at {}: no reply within {} ms ({} requests sent){}; is the device on and at this "
        "address and port?",
        address_.text(), options_.link_timeout.count(), stats_.requests_sent,
        refused_ ? "; the host answered that nothing listens on that port" : ""));
  }
  return stats_.last_reply;
}

DeviceInfo LateroTransport::info() {
  const LateroReply reply = probe();
  DeviceInfo info;
  info.backend = Backend::latero;
  info.name = "Latero at " + address_.text();
  info.serial = address_.text();
  info.firmware_version = describe_controller_status(reply.controller_status) + "; " +
                          describe_io_status(reply.io_status);
  info.protocol_version = kLateroVersion;
  info.layout = options_.layout;
  info.fifo_capacity_frames = 1;  // none: a frame plays when it arrives
  return info;
}

void LateroTransport::start(double rate_hz) {
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument(fmt::format("Latero stream rate {} Hz must be positive", rate_hz));
  }
  const LateroReply keep = stats_.last_reply;
  const bool had_reply = stats_.any_reply;
  drain(Clock::now());
  stats_ = {};
  stats_.last_reply = keep;
  stats_.any_reply = had_reply;
  outstanding_.clear();
  unanswered_since_ = {};
  rate_hz_ = rate_hz;
  period_ = nanoseconds(static_cast<std::int64_t>(std::llround(1e9 / rate_hz)));
  started_at_ = Clock::now();
  next_slot_ = started_at_ + period_;
  streaming_ = true;
}

void LateroTransport::send_at_slot(const std::array<std::uint8_t, kLateroBlades>& blades,
                                   bool is_frame) {
  const auto slot = next_slot_;
  if (Clock::now() + kSpin < slot) drain(slot - kSpin);
  while (Clock::now() < slot) receive_ready();
  LateroRequest r;
  r.type = LateroPacketType::full;
  r.dio_out = options_.dio_out;
  r.blade = blades;
  send_request(r);
  const auto sent = Clock::now();
  last_blades_ = blades;
  if (is_frame) {
    ++stats_.frames_sent;
    stats_.send_offset_s.push_back(std::chrono::duration<double>(sent - slot).count());
    stats_.send_time_s.push_back(std::chrono::duration<double>(sent - started_at_).count());
  }
  if (sent - slot > period_) ++stats_.late_frames;
  if (sent - slot > options_.max_catch_up) {
    // Too far behind: catching up would send a long burst that a device without a queue
    // shows as a jump, so the clock starts again from now.
    ++stats_.clock_restarts;
    next_slot_ = sent + period_;
  } else {
    // A little behind: keep the schedule, so that the movie keeps its length and rate.
    next_slot_ = slot + period_;
  }
}

bool LateroTransport::send_frame(std::span<const std::uint8_t> frame) {
  if (!streaming_) {
    throw TransportError(fmt::format("Latero at {}: send_frame before start", address_.text()));
  }
  std::array<std::int16_t, kLateroBlades> units{};
  tfw_frame_header header{};
  const tfw_result r =
      tfw_decode_frame(frame.data(), frame.size(), &header, units.data(), units.size());
  if (r != TFW_OK || header.contactor_count != kLateroBlades) {
    ++stats_.unplayable_frames;  // as a device would: counted, never played
    return true;
  }
  std::array<std::uint8_t, kLateroBlades> blades{};
  for (std::size_t i = 0; i < blades.size(); ++i) {
    blades[i] = blade_raw(from_wire_units(units[i]), options_.mapping);
  }
  send_at_slot(blades, true);
  check_link();
  return true;
}

void LateroTransport::stop() {
  if (!streaming_) return;
  streaming_ = false;
  // Ramp (linear in raw units) from where the blades are to centre, then centre exactly.
  const std::uint8_t centre = centre_raw(options_.mapping);
  const auto steps = std::max<std::int64_t>(
      1, std::llround(std::chrono::duration<double>(options_.stop_ramp).count() * rate_hz_));
  const auto from = last_blades_;
  for (std::int64_t k = 1; k <= steps; ++k) {
    const double w = static_cast<double>(k) / static_cast<double>(steps);
    std::array<std::uint8_t, kLateroBlades> blades{};
    for (std::size_t i = 0; i < blades.size(); ++i) {
      blades[i] = static_cast<std::uint8_t>(std::lround(from[i] + w * (centre - from[i])));
    }
    send_at_slot(blades, false);
  }
  drain(Clock::now() + options_.reply_timeout + std::chrono::milliseconds(1));
  // Whatever is still unanswered now missed its reply.
  stats_.missed_replies += outstanding_.size();
  outstanding_.clear();
}

DeviceStatus LateroTransport::status() {
  receive_ready();
  expire(Clock::now());
  DeviceStatus s;
  s.frames_received = stats_.frames_sent;
  s.frames_played = stats_.frames_sent;  // no queue: a frame plays when it arrives
  s.malformed = stats_.unplayable_frames;
  if (stats_.unplayable_frames > 0) s.rejected_by_reason["unplayable"] = stats_.unplayable_frames;
  s.fifo_fill = 0;
  s.fifo_capacity = 1;
  s.started = streaming_;
  s.streaming = streaming_;
  s.rate_hz = rate_hz_;
  return s;
}

void LateroTransport::wait(std::chrono::nanoseconds duration) {
  auto until = Clock::now() + duration;
  // Never sleep past the next slot: the frame due then would go out late.
  if (streaming_) until = std::min(until, next_slot_ - kSpin);
  drain(until);
  check_link();
}

LateroTiming summarize_timing(const LateroLinkStats& stats, double rate_hz) {
  LateroTiming t;
  t.frames = stats.send_time_s.size();
  std::vector<double> offsets_us;
  for (const double s : stats.send_offset_s) offsets_us.push_back(1e6 * s);
  std::sort(offsets_us.begin(), offsets_us.end());
  t.offset_p50_us = quantile(offsets_us, 0.50);
  t.offset_p99_us = quantile(offsets_us, 0.99);
  t.offset_max_us = offsets_us.empty() ? 0 : offsets_us.back();
  const auto& times = stats.send_time_s;
  if (times.size() >= 2) {
    t.achieved_rate_hz = static_cast<double>(times.size() - 1) / (times.back() - times.front());
    std::vector<double> jitter_us;
    for (std::size_t i = 1; i < times.size(); ++i) {
      jitter_us.push_back(1e6 * std::abs(times[i] - times[i - 1] - 1.0 / rate_hz));
    }
    std::sort(jitter_us.begin(), jitter_us.end());
    t.interval_jitter_p50_us = quantile(jitter_us, 0.50);
    t.interval_jitter_p99_us = quantile(jitter_us, 0.99);
  }
  return t;
}

std::string format_latero_link(const LateroLinkStats& stats, double rate_hz) {
  const LateroTiming t = summarize_timing(stats, rate_hz);
  std::string out = fmt::format(
      "frames      {} sent at {:.2f} Hz achieved ({:g} Hz asked), {} more than a period late, "
      "{} clock restarts\n",
      t.frames, t.achieved_rate_hz, rate_hz, stats.late_frames, stats.clock_restarts);
  out += fmt::format(
      "jitter      send time after its slot p50 {:.1f} us, p99 {:.1f} us, max {:.1f} us; "
      "interval error p50 {:.1f} us, p99 {:.1f} us\n",
      t.offset_p50_us, t.offset_p99_us, t.offset_max_us, t.interval_jitter_p50_us,
      t.interval_jitter_p99_us);
  out += fmt::format(
      "replies     {} requests, {} replies, {} missed ({} of them came late), {} malformed, "
      "{} unplayable frames\n",
      stats.requests_sent, stats.replies_received, stats.missed_replies, stats.late_replies,
      stats.malformed_replies, stats.unplayable_frames);
  return out;
}

}  // namespace tactile::display
