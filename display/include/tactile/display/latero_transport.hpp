#pragma once
// A Latero over UDP behind the Transport interface. The Latero has no FIFO: it moves its
// blades when a request arrives, so this transport owns the clock and sends each frame at its
// slot on the host clock (start time + k / rate). Every request should get one reply; replies
// that do not come are counted, and a device that stops answering altogether ends the stream
// with a TransportError naming its address. stop() ramps every blade back to centre.

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "tactile/display/latero_protocol.hpp"
#include "tactile/display/transport.hpp"

namespace tactile::display {

struct LateroAddress {
  std::string host;  // name, IPv4 or IPv6 address (without brackets)
  std::uint16_t port = kLateroDefaultPort;
  std::string text() const;  // "host:port", "[v6]:port"
};

// "HOST", "HOST:PORT", "[IPV6]" or "[IPV6]:PORT"; throws std::invalid_argument naming what is
// wrong (empty host, port not a number or outside 1..65535, unbalanced brackets).
LateroAddress parse_latero_address(const std::string& text);

struct LateroTransportOptions {
  movie::Layout layout = movie::latero_layout();
  LateroBladeMapping mapping;
  // A reply later than this after its request counts as missed (OpenLatero waits 5 ms).
  std::chrono::milliseconds reply_timeout{5};
  // No reply at all for this long (to the probe in info(), or while streaming): the device is
  // gone and the stream fails with a TransportError naming the address.
  std::chrono::milliseconds link_timeout{500};
  // A frame this late (host busy) restarts the schedule from now; less late ones are sent at
  // once and the schedule kept, so the movie keeps its rate and length.
  std::chrono::milliseconds max_catch_up{20};
  // stop() ramps the blades from where they are to centre over this time.
  std::chrono::milliseconds stop_ramp{20};
  std::uint16_t dio_out = 0x1000;  // what OpenLatero sends: one LED on
};

// What the sender saw, beyond the Transport's DeviceStatus.
struct LateroLinkStats {
  std::uint64_t requests_sent = 0;  // all requests (probe, frames, stop ramp)
  std::uint64_t frames_sent = 0;    // movie frames sent by send_frame
  std::uint64_t replies_received = 0;
  std::uint64_t missed_replies = 0;     // requests whose reply did not come in reply_timeout
  std::uint64_t late_replies = 0;       // replies that came after their request was missed
  std::uint64_t malformed_replies = 0;  // datagrams from the device that did not decode
  // The malformed replies by what was wrong (indexed by LateroPacketError), and how many of
  // them were the requests themselves coming back (a loop or an echo service, not a Latero).
  std::array<std::uint64_t, kLateroPacketErrorCount> malformed_by_error{};
  std::uint64_t echoed_requests = 0;
  std::uint64_t unplayable_frames = 0;  // frames handed to send_frame that were not valid
  std::uint64_t late_frames = 0;        // sent more than one period after their slot
  std::uint64_t clock_restarts = 0;     // times the schedule restarted (max_catch_up exceeded)
  // Every frame's send time relative to its slot on the host clock, and since start() (s).
  std::vector<double> send_offset_s;
  std::vector<double> send_time_s;
  LateroReply last_reply;
  bool any_reply = false;
};

// How well the frames kept to the host clock.
struct LateroTiming {
  std::uint64_t frames = 0;
  double achieved_rate_hz = 0;  // (frames - 1) / (last send - first send)
  // Lateness of each send after its slot, and |interval between sends - period|, in us.
  double offset_p50_us = 0, offset_p99_us = 0, offset_max_us = 0;
  double interval_jitter_p50_us = 0, interval_jitter_p99_us = 0;
};
LateroTiming summarize_timing(const LateroLinkStats& stats, double rate_hz);
// What the malformed replies were, for people: "10 malformed replies: wrong magic", or
// "12 malformed replies: 7 with a wrong magic byte, 5 oversized"; empty when there were none.
std::string describe_malformed_replies(const LateroLinkStats& stats);
// Lines for people: frames and rate, jitter, replies (missed, late, malformed).
std::string format_latero_link(const LateroLinkStats& stats, double rate_hz);

class LateroTransport : public Transport {
 public:
  // Opens a UDP socket towards `address` (resolved now; nothing is sent until info() or
  // start()). Throws TransportError when the name does not resolve.
  LateroTransport(LateroAddress address, LateroTransportOptions options = {});
  ~LateroTransport() override;

  // Probes the device with an IO request (blades untouched) and describes it: the Latero
  // layout, no FIFO (capacity 1), firmware = the status words. Throws TransportError when
  // nothing answers within link_timeout.
  DeviceInfo info() override;
  void start(double rate_hz) override;
  void stop() override;
  // Decodes the project's wire frame, maps it to blade bytes and sends it at its slot.
  bool send_frame(std::span<const std::uint8_t> frame) override;
  DeviceStatus status() override;
  void wait(std::chrono::nanoseconds duration) override;

  // One IO request and its reply (what `tactile devices --latero` prints).
  LateroReply probe();
  LateroLinkStats stats() const { return stats_; }
  const LateroAddress& address() const { return address_; }

 private:
  struct Outstanding {
    std::uint16_t sequence = 0;
    std::chrono::steady_clock::time_point sent_at;
  };
  void send_request(const LateroRequest& request);
  // Waits for the slot of the next frame on the host clock, then sends `blades`.
  void send_at_slot(const std::array<std::uint8_t, kLateroBlades>& blades, bool is_frame);
  // Reads every reply already there, without waiting.
  void receive_ready();
  // Counts requests older than reply_timeout as missed.
  void expire(std::chrono::steady_clock::time_point now);
  // Reads replies until `until`.
  void drain(std::chrono::steady_clock::time_point until);
  // Throws TransportError when nothing has answered for link_timeout.
  void check_link();
  // The error for a link on which only malformed replies came; `for_or_within` completes
  // "no valid reply ... 500 ms".
  TransportError nonsense_error(const char* for_or_within) const;

  LateroAddress address_;
  LateroTransportOptions options_;
  int socket_ = -1;
  std::uint16_t sequence_ = 0;
  std::deque<Outstanding> outstanding_;
  // Time of the first request sent since the last reply (zero: none waiting).
  std::chrono::steady_clock::time_point unanswered_since_{};
  bool refused_ = false;  // the host reported the port unreachable
  std::chrono::steady_clock::time_point started_at_{};
  std::chrono::steady_clock::time_point next_slot_{};
  std::chrono::nanoseconds period_{0};
  std::array<std::uint8_t, kLateroBlades> last_blades_{};
  bool streaming_ = false;
  double rate_hz_ = 0;
  LateroLinkStats stats_;
};

}  // namespace tactile::display
