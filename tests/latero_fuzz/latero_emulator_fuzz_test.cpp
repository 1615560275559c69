// Random datagrams (seeded, bounded) against the emulated Latero: each is judged here by the
// rules of docs/protocol.md, independently of the decoder, and the emulator must agree: count
// and drop what is malformed, answer what is well-formed with a reply that decodes, and move
// its blades only for well-formed FULL requests.

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <random>
#include <thread>

#include "tactile/display/latero_emulator.hpp"
#include "tactile/display/latero_transport.hpp"

namespace tactile::display {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;

// Mostly datagrams that look nearly right (valid header, then one thing wrong or nothing),
// some pure noise, lengths 0..160.
Bytes random_datagram(std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 160);
  std::uniform_int_distribution<int> pick(0, 9);
  Bytes b(static_cast<std::size_t>(length(rng)));
  for (auto& x : b) x = static_cast<std::uint8_t>(byte(rng));
  if (pick(rng) < 7 && b.size() >= 3) {
    b[0] = pick(rng) == 0 ? static_cast<std::uint8_t>(byte(rng)) : 0xCA;
    b[1] = pick(rng) == 0 ? static_cast<std::uint8_t>(byte(rng)) : 0x11;
    const std::uint8_t types[] = {0x01, 0x02, 0x03, 0x81, 0x00, 0x04};
    b[2] = types[std::uniform_int_distribution<int>(0, 5)(rng)];
  }
  return b;
}

// The protocol's rules, written out: what a controller accepts.
bool well_formed(const Bytes& b) {
  if (b.size() < 5 || b.size() > 100 || b[0] != 0xCA || b[1] != 0x11) return false;
  switch (b[2]) {
    case 0x01:
      return b.size() >= 79;
    case 0x02:
      return b.size() >= 15;
    case 0x03:
      return b.size() >= 10;
    default:
      return false;
  }
}

TEST(LateroFuzz, ModelAgreesWithTheRulesOnFiveThousandDatagrams) {
  std::mt19937 rng(20261124);
  LateroDeviceModel model;
  std::uint64_t expected_malformed = 0, expected_full = 0;
  auto blades = model.blades();
  for (int i = 0; i < 5000; ++i) {
    const Bytes b = random_datagram(rng);
    const bool ok = well_formed(b);
    const auto reply = model.handle(b, Clock::now());
    ASSERT_EQ(reply.has_value(), ok) << "datagram " << i;
    if (!ok) {
      ++expected_malformed;
      ASSERT_EQ(model.blades(), blades) << "a malformed datagram moved the blades, " << i;
      continue;
    }
    const auto r = decode_latero_reply(*reply);
    ASSERT_TRUE(r.packet) << latero_error_name(r.error);
    ASSERT_EQ(r.packet->sequence, (b[3] << 8) | b[4]);
    if (b[2] == 0x01) {
      ++expected_full;
      ASSERT_TRUE(std::equal(b.begin() + 15, b.begin() + 79, model.blades().begin()));
      blades = model.blades();
      ASSERT_EQ(r.packet->type, LateroPacketType::full_reply_page0);
    }
  }
  const auto& c = model.counters();
  EXPECT_EQ(c.datagrams, 5000u);
  EXPECT_EQ(c.malformed, expected_malformed);
  EXPECT_EQ(c.full_requests, expected_full);
  EXPECT_EQ(c.full_requests + c.io_requests + c.raw_requests + c.malformed, 5000u);
  std::uint64_t by_reason = 0;
  for (const auto& [reason, n] : c.malformed_by_reason) by_reason += n;
  EXPECT_EQ(by_reason, c.malformed);
  // The generator really exercised both sides and every reason.
  EXPECT_GT(expected_full, 50u);
  EXPECT_GT(expected_malformed, 1000u);
  for (const char* reason : {"too_short", "oversized", "bad_magic", "bad_version", "bad_type"}) {
    EXPECT_GT(c.malformed_by_reason.count(reason), 0u) << reason;
  }
}

TEST(LateroFuzz, EmulatorOverLoopbackCountsAndDropsMalformedDatagrams) {
  LateroEmulatorOptions o;
  o.port = 0;
  LateroEmulator emulator(o);
  std::thread server([&] { emulator.serve(Clock::now() + std::chrono::seconds(30)); });
  std::mt19937 rng(7);
  LateroTransport client({"127.0.0.1", emulator.port()});
  std::uint64_t expected_malformed = 0;
  const int n = 2000;
  {
    // Raw datagrams through a socket of our own, paced a little so none is lost to a full
    // receive buffer.
    const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(emulator.port());
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (int i = 0; i < n; ++i) {
      const Bytes b = random_datagram(rng);
      if (!well_formed(b)) ++expected_malformed;
      ASSERT_EQ(::sendto(s, b.data(), b.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
                static_cast<ssize_t>(b.size()));
      if (i % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::close(s);
  }
  // Still answering a well-formed request afterwards.
  const LateroReply r = client.probe();
  EXPECT_NE(r.io_status, 0);
  for (int i = 0; i < 200 && emulator.counters().datagrams < n + 1u; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  emulator.request_stop();
  server.join();
  const auto c = emulator.counters();
  EXPECT_EQ(c.datagrams, n + 1u);
  EXPECT_EQ(c.malformed, expected_malformed);
  EXPECT_EQ(c.full_requests + c.io_requests + c.raw_requests + c.malformed, n + 1u);
}

}  // namespace
}  // namespace tactile::display
