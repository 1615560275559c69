// The Latero transport against the emulated controller over loopback UDP (127.0.0.1 only),
// the emulated controller's model fed datagrams directly, and HOST:PORT parsing.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <poll.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <thread>

#include "../movie/test_movies.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/latero_emulator.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/player.hpp"

namespace tactile::display {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

// An emulator on a free loopback port, served by a thread for the test's lifetime.
class RunningEmulator {
 public:
  explicit RunningEmulator(LateroEmulatorOptions options = {})
      : emulator_([&] {
          options.bind_address = "127.0.0.1";
          options.port = 0;
          return options;
        }()) {
    thread_ = std::thread([this] { emulator_.serve(Clock::now() + std::chrono::seconds(60)); });
  }
  ~RunningEmulator() {
    emulator_.request_stop();
    thread_.join();
  }
  LateroEmulator& operator*() { return emulator_; }
  LateroEmulator* operator->() { return &emulator_; }
  LateroAddress address() const { return {"127.0.0.1", emulator_.port()}; }

 private:
  LateroEmulator emulator_;
  std::thread thread_;
};

// Generous for a loaded test machine: only the loss test's dropped replies should miss.
LateroTransportOptions patient() {
  LateroTransportOptions o;
  o.reply_timeout = std::chrono::milliseconds(200);
  o.link_timeout = std::chrono::milliseconds(2000);
  return o;
}

TEST(LateroAddress, ParsesHostAndPort) {
  EXPECT_EQ(parse_latero_address("127.0.0.1").port, 8900);
  const auto a = parse_latero_address("127.0.0.1:9001");
  EXPECT_EQ(a.host, "127.0.0.1");
  EXPECT_EQ(a.port, 9001);
  EXPECT_EQ(a.text(), "127.0.0.1:9001");
  const auto v6 = parse_latero_address("[::1]:65535");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 65535);
  EXPECT_EQ(v6.text(), "[::1]:65535");
  EXPECT_EQ(parse_latero_address("::1").port, 8900);
  EXPECT_EQ(parse_latero_address("latero.local:1").host, "latero.local");
}

TEST(LateroAddress, RefusesBadInputByName) {
  auto message = [](const std::string& text) {
    try {
      parse_latero_address(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message("127.0.0.1:0"), HasSubstr("outside 1..65535"));
  EXPECT_THAT(message("127.0.0.1:65536"), HasSubstr("outside 1..65535"));
  EXPECT_THAT(message("127.0.0.1:99999999"), HasSubstr("not a number"));
  EXPECT_THAT(message("127.0.0.1:http"), HasSubstr("not a number"));
  EXPECT_THAT(message("127.0.0.1:"), HasSubstr("not a number"));
  EXPECT_THAT(message(":8900"), HasSubstr("no host"));
  EXPECT_THAT(message(""), HasSubstr("no host"));
  EXPECT_THAT(message("[::1"), HasSubstr("without ']'"));
  EXPECT_THAT(message("[::1]8900"), HasSubstr("expected ':PORT'"));
}

TEST(LateroModel, AnswersFullIoAndRawRequestsAsTheControllerDoes) {
  LateroEmulatorOptions o;
  o.fpga_version = 2;
  o.fpga_revision = 3;
  LateroDeviceModel model(o);
  const auto t0 = Clock::now();
  LateroRequest full;
  full.sequence = 41;
  for (int i = 0; i < kLateroBlades; ++i)
    full.blade[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  const auto reply = model.handle(encode_latero_request(full), t0);
  ASSERT_TRUE(reply);
  ASSERT_EQ(reply->size(), kLateroDatagramBytes);
  const auto r = decode_latero_reply(*reply);
  ASSERT_TRUE(r.packet);
  EXPECT_EQ(r.packet->type, LateroPacketType::full_reply_page0);
  EXPECT_EQ(r.packet->sequence, 41);
  const auto status = decode_controller_status(r.packet->controller_status);
  EXPECT_EQ(status.fpga_version, 2);
  EXPECT_EQ(status.fpga_revision, 3);
  EXPECT_TRUE(status.high_voltage_active);
  EXPECT_NE(r.packet->io_status, 0);
  EXPECT_EQ(r.packet->dio_in & (kLateroButton0Mask | kLateroButton1Mask),
            kLateroButton0Mask | kLateroButton1Mask);  // released: bits high
  EXPECT_EQ(model.blades(), full.blade);

  // Buttons are active-low.
  model.set_buttons(true, false);
  LateroRequest io;
  io.type = LateroPacketType::io;
  const auto b = decode_latero_reply(*model.handle(encode_latero_request(io), t0));
  EXPECT_EQ(b.packet->dio_in & kLateroButton0Mask, 0);
  EXPECT_NE(b.packet->dio_in & kLateroButton1Mask, 0);
  EXPECT_EQ(model.blades(), full.blade);  // IO requests leave the blades alone

  // RAW: a write is read back at the same place, not elsewhere.
  LateroRequest w;
  w.type = LateroPacketType::raw;
  w.raw_command = kLateroRawWrite | kLateroRawIoBoard;
  w.raw_address = 0x18;
  w.raw_data = 0x00F0;
  model.handle(encode_latero_request(w), t0);
  LateroRequest rd = w;
  rd.raw_command = kLateroRawRead | kLateroRawIoBoard;
  const auto back = decode_latero_reply(*model.handle(encode_latero_request(rd), t0));
  EXPECT_EQ(back.packet->type, LateroPacketType::raw_reply);
  EXPECT_EQ(back.packet->raw_data, 0x00F0);
  rd.raw_command = kLateroRawRead | kLateroRawController;
  EXPECT_EQ(decode_latero_reply(*model.handle(encode_latero_request(rd), t0)).packet->raw_data, 0);

  // High voltage: switched on once while requests keep coming, again after a pause.
  model.handle(encode_latero_request(io), t0 + std::chrono::milliseconds(50));
  model.handle(encode_latero_request(io), t0 + std::chrono::milliseconds(400));
  EXPECT_EQ(model.counters().high_voltage_enables, 2u);
  EXPECT_EQ(model.counters().full_requests, 1u);
  EXPECT_EQ(model.counters().io_requests, 3u);
  EXPECT_EQ(model.counters().raw_requests, 3u);
}

TEST(LateroModel, CountsAndDropsMalformedDatagrams) {
  LateroDeviceModel model;
  const auto before = model.blades();
  std::vector<std::uint8_t> bad = encode_latero_request(LateroRequest{});
  bad[0] = 0x00;
  EXPECT_FALSE(model.handle(bad, Clock::now()));
  bad[0] = kLateroMagic;
  bad[1] = 0x21;
  EXPECT_FALSE(model.handle(bad, Clock::now()));
  EXPECT_FALSE(model.handle(std::vector<std::uint8_t>(3, 0xCA), Clock::now()));
  EXPECT_FALSE(model.handle(std::vector<std::uint8_t>(101, 0xCA), Clock::now()));
  const auto& c = model.counters();
  EXPECT_EQ(c.malformed, 4u);
  EXPECT_EQ(c.malformed_by_reason.at("bad_magic"), 1u);
  EXPECT_EQ(c.malformed_by_reason.at("bad_version"), 1u);
  EXPECT_EQ(c.malformed_by_reason.at("too_short"), 1u);
  EXPECT_EQ(c.malformed_by_reason.at("oversized"), 1u);
  EXPECT_EQ(c.replies_sent, 0u);
  EXPECT_EQ(model.blades(), before);  // never played
}

TEST(LateroModel, LeavesOutEveryNthReply) {
  LateroEmulatorOptions o;
  o.drop_every_nth_reply = 3;
  LateroDeviceModel model(o);
  int answered = 0;
  for (int i = 0; i < 10; ++i) {
    if (model.handle(encode_latero_request(LateroRequest{}), Clock::now())) ++answered;
  }
  EXPECT_EQ(answered, 7);  // the 3rd, 6th and 9th are left out
  EXPECT_EQ(model.counters().replies_dropped, 3u);
}

TEST(LateroTransport, ProbeDescribesTheDevice) {
  LateroEmulatorOptions o;
  o.fpga_version = 3;
  o.fpga_revision = 1;
  RunningEmulator emulator(o);
  LateroTransport t(emulator.address(), patient());
  const DeviceInfo info = t.info();
  EXPECT_EQ(info.backend, Backend::latero);
  EXPECT_THAT(info.name, HasSubstr(emulator.address().text()));
  EXPECT_THAT(info.firmware_version, HasSubstr("FPGA 3.1"));
  EXPECT_THAT(info.firmware_version, HasSubstr("high voltage active"));
  EXPECT_THAT(info.firmware_version, HasSubstr("IO board FPGA 1.0"));
  EXPECT_EQ(info.layout.name, "latero");
  EXPECT_EQ(emulator->counters().io_requests, 1u);
  EXPECT_EQ(emulator->counters().full_requests, 0u);  // probing moves no blade
}

TEST(LateroTransport, WorksOverIpv6Loopback) {
  LateroEmulatorOptions o;
  o.bind_address = "::1";
  o.port = 0;
  std::unique_ptr<LateroEmulator> emulator;
  try {
    emulator = std::make_unique<LateroEmulator>(o);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  EXPECT_EQ(emulator->address(), "[::1]:" + std::to_string(emulator->port()));
  std::thread server([&] { emulator->serve(Clock::now() + std::chrono::seconds(10)); });
  LateroTransport t(parse_latero_address(emulator->address()), patient());
  EXPECT_THAT(t.info().name, HasSubstr("[::1]:"));
  emulator->request_stop();
  server.join();
  EXPECT_EQ(emulator->counters().io_requests, 1u);
}

TEST(LateroTransport, PlaysEveryFramePacedByTheHostClockAndStopsAtCentre) {
  RunningEmulator emulator;
  LateroTransport t(emulator.address(), patient());
  const movie::TactileMovie movie =
      movie::testing::sine_movie(movie::latero_layout(), 750, 300, 90);  // 0.4 s
  const auto wall0 = Clock::now();
  const PlaybackReport r = play_movie(movie, t);
  const double wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  const LateroLinkStats s = t.stats();
  EXPECT_EQ(r.frames_sent, r.movie_frames + r.ramp_frames);
  EXPECT_EQ(s.frames_sent, static_cast<std::uint64_t>(r.frames_sent));
  ASSERT_EQ(s.send_offset_s.size(), s.frames_sent);
  // Never early: each frame leaves at or after its slot, so the stream lasts at least as long
  // as its frames at 750 Hz.
  for (const double d : s.send_offset_s) ASSERT_GE(d, 0.0);
  EXPECT_GE(wall_s, static_cast<double>(r.frames_sent) / 750.0);
  const LateroEmulatorCounters c = emulator->counters();
  // Every request reached the emulator: the frames and the stop ramp (all FULL), one probe.
  EXPECT_EQ(c.full_requests, s.requests_sent);
  EXPECT_GT(s.requests_sent, s.frames_sent);  // the stop ramp
  EXPECT_EQ(c.io_requests, 1u);
  EXPECT_EQ(c.malformed, 0u);
  // Every request answered in time or counted as missed.
  EXPECT_EQ(s.requests_sent, s.replies_received - s.late_replies + s.missed_replies);
  EXPECT_EQ(c.replies_sent, s.replies_received + 1);  // + the probe's reply
  // The clean stop left every blade at centre.
  const auto blades = emulator->blades();
  EXPECT_TRUE(std::all_of(blades.begin(), blades.end(), [](std::uint8_t b) { return b == 75; }));
}

// The path `tactile play --latero` and Python's play(backend="latero") share: play_anywhere
// with a Latero asked for goes there and nowhere else, with the blade mapping it was given.
TEST(LateroPlay, PlayAnywhereSendsTheMovieToTheLateroAskedForWithItsBladeMapping) {
  RunningEmulator emulator;
  ResolvedPlay request;
  request.headless = true;  // not looked at when a Latero is asked for
  request.latero = LateroPlayTarget{emulator.address().text(), {}};
  request.latero->mapping.centre_raw = 128;
  request.latero->mapping.max_raw = 255;
  std::string said;
  const PlayResult r = play_anywhere(
      movie::testing::sine_movie(movie::latero_layout(), 750, 150, 40), request,
      [&](const std::string& text) { said += text; }, PlayBackends{});
  EXPECT_EQ(r.target, PlaybackTarget::latero);
  ASSERT_TRUE(r.report && r.latero_link && r.latero_address);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.latero_address->port, emulator->port());
  EXPECT_EQ(r.report->movie_frames, 150);
  EXPECT_EQ(r.latero_link->frames_sent, static_cast<std::uint64_t>(r.report->frames_sent));
  const LateroEmulatorCounters c = emulator->counters();
  EXPECT_EQ(c.full_requests, r.latero_link->requests_sent);
  EXPECT_EQ(c.io_requests, 1u);
  // Stopped at the centre it was given, not OpenLatero's 75.
  const auto blades = emulator->blades();
  EXPECT_TRUE(std::all_of(blades.begin(), blades.end(), [](std::uint8_t b) { return b == 128; }));
  EXPECT_THAT(said, HasSubstr("play: streaming to the Latero at " + emulator.address().text()));
  EXPECT_THAT(said, HasSubstr("raw 128 at rest"));
}

TEST(LateroPlay, RefusesAnotherLayoutOrABadMappingBeforeSendingAnything) {
  RunningEmulator emulator;
  ResolvedPlay request;
  request.latero = LateroPlayTarget{emulator.address().text(), {}};
  const auto quiet = [](const std::string&) {};
  try {
    play_anywhere(movie::testing::sine_movie(movie::stress_layout(), 700, 10, 10), request, quiet,
                  PlayBackends{});
    ADD_FAILURE() << "a stress movie was played on a Latero";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'stress'"));
    EXPECT_THAT(e.what(), HasSubstr("--layout latero"));
  }
  request.latero->mapping.centre_raw = 200;
  EXPECT_THROW(play_anywhere(movie::testing::sine_movie(movie::latero_layout(), 750, 10, 10),
                             request, quiet, PlayBackends{}),
               std::invalid_argument);
  EXPECT_EQ(emulator->counters().datagrams, 0u);
}

TEST(LateroTransport, CountsRepliesTheDeviceLeftOut) {
  LateroEmulatorOptions o;
  o.drop_every_nth_reply = 7;
  RunningEmulator emulator(o);
  LateroTransport t(emulator.address(), patient());
  play_movie(movie::testing::sine_movie(movie::latero_layout(), 750, 150, 50), t);
  // On a loaded machine the emulator can take the last requests after the stream's own wait
  // for replies has ended: let it answer (or drop) every request sent, then let the transport
  // read what came late, before comparing the two sides' counts.
  const std::uint64_t sent = t.stats().requests_sent;
  const auto settled = [&] {
    const LateroEmulatorCounters now = emulator->counters();
    return now.datagrams >= sent && now.replies_sent + now.replies_dropped >= now.datagrams;
  };
  for (int i = 0; i < 5000 && !settled(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(settled()) << "the emulator did not take every request within 5 s";
  t.status();
  const LateroLinkStats s = t.stats();
  const LateroEmulatorCounters c = emulator->counters();
  ASSERT_GT(c.replies_dropped, 20u);
  // The probe's reply was the first and was sent; all dropped ones belong to the stream.
  EXPECT_EQ(s.missed_replies - s.late_replies, c.replies_dropped);
  EXPECT_EQ(s.replies_received + 1, c.replies_sent);
}

TEST(LateroTransport, StopMidStreamRampsEveryBladeToCentre) {
  RunningEmulator emulator;
  LateroTransportOptions o = patient();
  o.mapping.centre_raw = 128;
  o.mapping.max_raw = 255;
  LateroTransport t(emulator.address(), o);
  t.info();
  t.start(750);
  std::vector<float> frame(64, 100.0f);
  for (std::uint32_t k = 0; k < 5; ++k) t.send_frame(encode_frame(frame, k));
  // Wait for the emulator to play the last frame before looking at it.
  for (int i = 0; i < 200 && emulator->counters().full_requests < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(emulator->blades()[0], 203);  // 128 + 75
  t.stop();
  for (int i = 0; i < 200 && emulator->blades()[0] != 128; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const auto blades = emulator->blades();
  EXPECT_TRUE(std::all_of(blades.begin(), blades.end(), [](std::uint8_t b) { return b == 128; }));
  EXPECT_EQ(emulator->counters().full_requests, t.stats().requests_sent);
}

TEST(LateroTransport, RefusesFramesItCannotPlayWithoutSendingThem) {
  RunningEmulator emulator;
  LateroTransport t(emulator.address(), patient());
  t.info();
  t.start(750);
  std::vector<std::uint8_t> frame = encode_frame(std::vector<float>(64, 1.0f), 0);
  frame[20] ^= 0xFF;  // checksum no longer matches
  t.send_frame(frame);
  t.send_frame(encode_frame(std::vector<float>(100, 1.0f), 1));  // a STReSS frame
  EXPECT_EQ(t.stats().unplayable_frames, 2u);
  EXPECT_EQ(t.stats().frames_sent, 0u);
  EXPECT_EQ(t.status().malformed, 2u);
}

TEST(LateroTransport, SilentDeviceTimesOutNamingTheAddress) {
  // A bound socket that never answers: no ICMP, pure silence.
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  const auto port = ntohs(a.sin_port);
  LateroTransportOptions o;
  o.link_timeout = std::chrono::milliseconds(150);
  LateroTransport t({"127.0.0.1", port}, o);
  const auto t0 = Clock::now();
  try {
    t.info();
    ADD_FAILURE() << "no error";
  } catch (const TransportError& e) {
    EXPECT_THAT(e.what(), HasSubstr("127.0.0.1:" + std::to_string(port)));
    EXPECT_THAT(e.what(), HasSubstr("no reply within 150 ms"));
  }
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(2));
  ::close(s);
}

// A peer on 127.0.0.1 that answers each request with what `answer` makes of it, at most 400
// times and for at most 10 s: a device that talks, but not the Latero protocol.
class NonsenseDevice {
 public:
  using Answer = std::function<std::vector<std::uint8_t>(const std::vector<std::uint8_t>&)>;
  explicit NonsenseDevice(Answer answer) : answer_(std::move(answer)) {
    socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(socket_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ::getsockname(socket_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~NonsenseDevice() {
    stop_ = true;
    thread_.join();
    ::close(socket_);
  }
  LateroAddress address() const { return {"127.0.0.1", port_}; }

 private:
  void serve() {
    const auto end = Clock::now() + std::chrono::seconds(10);
    for (int answered = 0; !stop_ && answered < 400 && Clock::now() < end;) {
      pollfd p{socket_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      std::vector<std::uint8_t> request(2048);
      sockaddr_in from{};
      socklen_t len = sizeof from;
      const ssize_t n = ::recvfrom(socket_, request.data(), request.size(), 0,
                                   reinterpret_cast<sockaddr*>(&from), &len);
      if (n <= 0) continue;
      request.resize(static_cast<std::size_t>(n));
      const auto reply = answer_(request);
      ::sendto(socket_, reply.data(), reply.size(), 0, reinterpret_cast<sockaddr*>(&from), len);
      ++answered;
    }
  }
  Answer answer_;
  int socket_ = -1;
  std::uint16_t port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string probe_error(const LateroAddress& address) {
  LateroTransportOptions o;
  o.link_timeout = std::chrono::milliseconds(150);
  LateroTransport t(address, o);
  try {
    t.info();
  } catch (const TransportError& e) {
    return e.what();
  }
  return "(no error)";
}

// A device that answers nonsense is reported as such, with what was wrong, never as silence.
TEST(LateroTransport, DeviceAnsweringNonsenseIsReportedAsSuch) {
  const auto valid = encode_latero_reply(LateroReply{});
  {
    NonsenseDevice d([&](const std::vector<std::uint8_t>&) {
      auto r = valid;
      r[0] ^= 0xFF;
      return r;
    });
    const std::string e = probe_error(d.address());
    EXPECT_THAT(e, HasSubstr("Latero at " + d.address().text() + " answered "));
    EXPECT_THAT(e, HasSubstr(" malformed replies: wrong magic, and no valid reply within 150 ms"));
    EXPECT_THAT(e, ::testing::Not(HasSubstr("no reply within")));
  }
  {
    NonsenseDevice d([&](const std::vector<std::uint8_t>&) {
      auto r = valid;
      r.resize(4000, 0xAB);
      return r;
    });
    EXPECT_THAT(probe_error(d.address()), HasSubstr("malformed replies: oversized"));
  }
  {
    NonsenseDevice d([](const std::vector<std::uint8_t>& request) { return request; });
    EXPECT_THAT(probe_error(d.address()),
                HasSubstr("malformed replies: our own requests echoed back"));
  }
  {
    std::uint32_t state = 12345;  // fixed seed: the same bytes every run
    NonsenseDevice d([&](const std::vector<std::uint8_t>&) {
      std::vector<std::uint8_t> r(1 + state % 150);
      for (auto& b : r) {
        state = state * 1664525u + 1013904223u;
        b = static_cast<std::uint8_t>(state >> 24);
      }
      r[0] = static_cast<std::uint8_t>(r[0] == kLateroMagic ? r[0] + 1 : r[0]);
      return r;
    });
    const std::string e = probe_error(d.address());
    EXPECT_THAT(e, HasSubstr(" malformed replies: "));
    EXPECT_THAT(e, HasSubstr("no valid reply within 150 ms"));
  }
}

// While streaming, a device whose answers turn into nonsense ends the stream saying so.
TEST(LateroTransport, DeviceWhoseRepliesTurnMalformedMidStreamIsNamed) {
  int good = 3;
  NonsenseDevice d([&](const std::vector<std::uint8_t>& request) {
    LateroReply reply;
    reply.sequence = static_cast<std::uint16_t>((request[3] << 8) | request[4]);
    auto r = encode_latero_reply(reply);
    if (good-- <= 0) r[1] ^= 0xFF;  // the version byte
    return r;
  });
  LateroTransportOptions o;
  o.link_timeout = std::chrono::milliseconds(100);
  o.reply_timeout = std::chrono::milliseconds(100);
  LateroTransport t(d.address(), o);
  t.info();
  t.start(750);
  const std::vector<float> frame(64, 0.0f);
  try {
    for (std::uint32_t k = 0; k < 750; ++k) t.send_frame(encode_frame(frame, k));
    ADD_FAILURE() << "no error";
  } catch (const TransportError& e) {
    EXPECT_THAT(e.what(), HasSubstr("malformed replies: wrong protocol version, and no valid "
                                    "reply for 100 ms"));
  }
}

TEST(LateroTransport, DeviceThatGoesAwayMidStreamEndsTheStream) {
  auto emulator = std::make_unique<RunningEmulator>();
  LateroTransportOptions o;
  o.link_timeout = std::chrono::milliseconds(100);
  LateroTransport t(emulator->address(), o);
  t.info();
  t.start(750);
  const std::vector<float> frame(64, 0.0f);
  t.send_frame(encode_frame(frame, 0));
  emulator.reset();  // the device is gone
  try {
    for (std::uint32_t k = 1; k < 750; ++k) t.send_frame(encode_frame(frame, k));
    ADD_FAILURE() << "no error after 1 s of silence";
  } catch (const TransportError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no reply for 100 ms"));
    EXPECT_THAT(e.what(), HasSubstr("nothing listens"));  // loopback reports the closed port
  }
}

}  // namespace
}  // namespace tactile::display
