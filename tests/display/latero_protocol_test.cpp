// The Latero packet codec, checked byte by byte against a reader written here from the table
// in docs/protocol.md ("Latero"), independently of the encoder.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tactile/display/latero_protocol.hpp"

namespace tactile::display {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Independent reader: each field by its documented offset and width, big-endian, into a map
// of field name -> value.
std::map<std::string, std::uint32_t> read_fields(const Bytes& b) {
  auto be = [&](std::size_t offset, std::size_t width) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < width; ++i) v = v * 256 + b.at(offset + i);
    return v;
  };
  std::map<std::string, std::uint32_t> f;
  f["magic"] = be(0, 1);
  f["version"] = be(1, 1);
  f["type"] = be(2, 1);
  f["seq"] = be(3, 2);
  const auto type = f["type"];
  if (type == 0x01 || type == 0x02) {
    f["dio_out"] = be(5, 2);
    for (int i = 0; i < 4; ++i) f["dac" + std::to_string(i)] = be(7 + 2 * i, 2);
    if (type == 0x01) {
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
          f["blade_y" + std::to_string(y) + "x" + std::to_string(x)] = be(15 + y * 8 + x, 1);
        }
      }
    }
  } else if (type == 0x03 || type == 0x83) {
    f["command"] = be(5, 1);
    f["address"] = be(6, 2);
    f["data"] = be(8, 2);
  } else if (type == 0x81 || type == 0x82) {
    f["dio_in"] = be(5, 2);
    f["ctrlstatus"] = be(7, 2);
    f["iostatus"] = be(9, 2);
    for (int i = 0; i < 4; ++i) f["quad" + std::to_string(i)] = be(11 + 4 * i, 4);
    for (int i = 0; i < 4; ++i) f["adc" + std::to_string(i)] = be(27 + 2 * i, 2);
  }
  return f;
}

LateroRequest full_request() {
  LateroRequest r;
  r.type = LateroPacketType::full;
  r.sequence = 0xBEEF;
  r.dio_out = 0x1234;
  r.dac = {0x0102, 0xA0B0, 0xFFFF, 0x0000};
  for (int i = 0; i < kLateroBlades; ++i)
    r.blade[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(3 * i + 1);
  return r;
}

TEST(LateroProtocol, FullRequestBytesMatchTheDocumentedLayout) {
  const Bytes b = encode_latero_request(full_request());
  ASSERT_EQ(b.size(), 100u);
  const auto f = read_fields(b);
  EXPECT_EQ(f.at("magic"), 0xCAu);
  EXPECT_EQ(f.at("version"), 0x11u);
  EXPECT_EQ(f.at("type"), 0x01u);
  EXPECT_EQ(f.at("seq"), 0xBEEFu);
  EXPECT_EQ(f.at("dio_out"), 0x1234u);
  EXPECT_EQ(f.at("dac0"), 0x0102u);
  EXPECT_EQ(f.at("dac1"), 0xA0B0u);
  EXPECT_EQ(f.at("dac2"), 0xFFFFu);
  EXPECT_EQ(f.at("dac3"), 0u);
  // Row-major: blade (x, y) is request index y * 8 + x, whose value is 3 * index + 1.
  EXPECT_EQ(f.at("blade_y0x0"), 1u);
  EXPECT_EQ(f.at("blade_y0x7"), 22u);
  EXPECT_EQ(f.at("blade_y1x0"), 25u);
  EXPECT_EQ(f.at("blade_y7x7"), 190u);
  // Big-endian: the high byte first.
  EXPECT_EQ(b[5], 0x12);
  EXPECT_EQ(b[6], 0x34);
  for (std::size_t i = 79; i < 100; ++i) EXPECT_EQ(b[i], 0) << "padding byte " << i;
}

TEST(LateroProtocol, IoRequestCarriesNoBlades) {
  LateroRequest r = full_request();
  r.type = LateroPacketType::io;
  const Bytes b = encode_latero_request(r);
  const auto f = read_fields(b);
  EXPECT_EQ(f.at("type"), 0x02u);
  EXPECT_EQ(f.at("dio_out"), 0x1234u);
  EXPECT_EQ(f.at("dac1"), 0xA0B0u);
  for (std::size_t i = 15; i < 100; ++i) EXPECT_EQ(b[i], 0) << "byte " << i;
}

TEST(LateroProtocol, RawRequestAndReplyLayout) {
  LateroRequest r;
  r.type = LateroPacketType::raw;
  r.raw_command = kLateroRawRead | kLateroRawIoBoard;
  r.raw_address = 0x0018;
  r.raw_data = 0xABCD;
  const auto f = read_fields(encode_latero_request(r));
  EXPECT_EQ(f.at("type"), 0x03u);
  EXPECT_EQ(f.at("command"), 0x21u);
  EXPECT_EQ(f.at("address"), 0x18u);
  EXPECT_EQ(f.at("data"), 0xABCDu);

  LateroReply reply;
  reply.type = LateroPacketType::raw_reply;
  reply.raw_command = 0x12;
  reply.raw_address = 0x0102;
  reply.raw_data = 0x7F00;
  const auto g = read_fields(encode_latero_reply(reply));
  EXPECT_EQ(g.at("type"), 0x83u);
  EXPECT_EQ(g.at("command"), 0x12u);
  EXPECT_EQ(g.at("address"), 0x0102u);
  EXPECT_EQ(g.at("data"), 0x7F00u);
}

TEST(LateroProtocol, FullReplyBytesMatchTheDocumentedLayout) {
  LateroReply r;
  r.type = LateroPacketType::full_reply_page1;
  r.sequence = 7;
  r.dio_in = 0xFFBF;  // button 0 held
  r.controller_status = 0x0124;
  r.io_status = 0x0100;
  r.encoder = {0x01020304u, 0xFFFFFFFFu, 0u, 0x80000000u};
  r.adc = {1, 2, 0x8000, 0xFFFF};
  const Bytes b = encode_latero_reply(r);
  ASSERT_EQ(b.size(), 100u);
  const auto f = read_fields(b);
  EXPECT_EQ(f.at("type"), 0x82u);
  EXPECT_EQ(f.at("seq"), 7u);
  EXPECT_EQ(f.at("dio_in"), 0xFFBFu);
  EXPECT_EQ(f.at("ctrlstatus"), 0x0124u);
  EXPECT_EQ(f.at("iostatus"), 0x0100u);
  EXPECT_EQ(f.at("quad0"), 0x01020304u);
  EXPECT_EQ(f.at("quad1"), 0xFFFFFFFFu);
  EXPECT_EQ(f.at("quad3"), 0x80000000u);
  EXPECT_EQ(f.at("adc2"), 0x8000u);
  EXPECT_EQ(f.at("adc3"), 0xFFFFu);
  EXPECT_EQ(b[11], 0x01);  // encoder 0, high byte first
  EXPECT_EQ(b[14], 0x04);
  for (std::size_t i = 35; i < 100; ++i) EXPECT_EQ(b[i], 0) << "padding byte " << i;
}

TEST(LateroProtocol, DecodersReadBackWhatTheEncodersWrote) {
  const LateroRequest r = full_request();
  const auto d = decode_latero_request(encode_latero_request(r));
  ASSERT_TRUE(d.packet) << latero_error_name(d.error);
  EXPECT_EQ(d.packet->sequence, r.sequence);
  EXPECT_EQ(d.packet->dio_out, r.dio_out);
  EXPECT_EQ(d.packet->dac, r.dac);
  EXPECT_EQ(d.packet->blade, r.blade);

  LateroReply reply;
  reply.dio_in = 0x0060;
  reply.controller_status = 0x0114;
  reply.io_status = 0x0100;
  reply.encoder = {1, 2, 3, 0xDEADBEEF};
  reply.adc = {9, 8, 7, 6};
  const auto e = decode_latero_reply(encode_latero_reply(reply));
  ASSERT_TRUE(e.packet) << latero_error_name(e.error);
  EXPECT_EQ(e.packet->type, LateroPacketType::full_reply_page0);
  EXPECT_EQ(e.packet->dio_in, 0x0060);
  EXPECT_EQ(e.packet->encoder, reply.encoder);
  EXPECT_EQ(e.packet->adc, reply.adc);
}

TEST(LateroProtocol, MalformedDatagramsGiveNamedErrors) {
  const Bytes good = encode_latero_request(full_request());
  auto error_of = [](const Bytes& b) { return decode_latero_request(b).error; };
  EXPECT_EQ(error_of({}), LateroPacketError::too_short);
  EXPECT_EQ(error_of({0xCA, 0x11}), LateroPacketError::too_short);
  EXPECT_EQ(error_of(Bytes(good.begin(), good.begin() + 78)), LateroPacketError::too_short);
  EXPECT_EQ(error_of(Bytes(good.begin(), good.begin() + 79)), LateroPacketError::none);
  Bytes big = good;
  big.push_back(0);
  EXPECT_EQ(error_of(big), LateroPacketError::oversized);
  Bytes b = good;
  b[0] = 0xCB;
  EXPECT_EQ(error_of(b), LateroPacketError::bad_magic);
  b = good;
  b[1] = 0x12;
  EXPECT_EQ(error_of(b), LateroPacketError::bad_version);
  for (const std::uint8_t type : {0x00, 0x04, 0x81, 0x83, 0xFF}) {
    b = good;
    b[2] = type;
    EXPECT_EQ(error_of(b), LateroPacketError::bad_type) << int{type};
  }
  // A reply decoder refuses requests, and names the error.
  const auto r = decode_latero_reply(good);
  EXPECT_FALSE(r.packet);
  EXPECT_EQ(r.error, LateroPacketError::bad_type);
  EXPECT_STREQ(latero_error_name(r.error), "bad_type");
  EXPECT_STREQ(latero_error_name(LateroPacketError::oversized), "oversized");
  // An IO request needs only its 15 bytes; a RAW request its 10.
  Bytes io = good;
  io[2] = 0x02;
  EXPECT_EQ(error_of(Bytes(io.begin(), io.begin() + 15)), LateroPacketError::none);
  EXPECT_EQ(error_of(Bytes(io.begin(), io.begin() + 14)), LateroPacketError::too_short);
}

TEST(LateroProtocol, StatusWordsDecode) {
  // FPGA 1.2, high voltage active, page 1.
  const LateroControllerStatus s = decode_controller_status(0x0125);
  EXPECT_EQ(s.fpga_version, 1);
  EXPECT_EQ(s.fpga_revision, 2);
  EXPECT_TRUE(s.high_voltage_active);
  EXPECT_FALSE(s.high_voltage_powered_off);
  EXPECT_EQ(s.active_page, 1);
  EXPECT_EQ(encode_controller_status(s), 0x0125);
  EXPECT_THAT(describe_controller_status(0x0122), ::testing::HasSubstr("powered off"));
  EXPECT_THAT(describe_io_status(0), ::testing::HasSubstr("no IO board"));
  EXPECT_THAT(describe_io_status(0x0130), ::testing::HasSubstr("FPGA 1.3"));
}

TEST(LateroProtocol, BladeMappingFollowsOpenLateroByDefault) {
  const LateroBladeMapping m;
  // raw = (0.5 - 0.5 v') * 150 with v' = -deflection / 100 um (TactileDisplay's sign).
  EXPECT_EQ(blade_raw(0, m), 75);
  EXPECT_EQ(blade_raw(100, m), 150);
  EXPECT_EQ(blade_raw(-100, m), 0);
  EXPECT_EQ(blade_raw(50, m), 113);    // 112.5 rounds away from zero
  EXPECT_EQ(blade_raw(1000, m), 150);  // clamped to max_raw
  EXPECT_EQ(blade_raw(-1000, m), 0);
  EXPECT_NEAR(blade_deflection_um(blade_raw(-40, m), m), -40, 100.0 / 75);
  LateroBladeMapping c;
  c.centre_raw = 128;
  c.raw_per_unit = -100;
  c.max_raw = 255;
  EXPECT_EQ(blade_raw(0, c), 128);
  EXPECT_EQ(blade_raw(100, c), 28);
  EXPECT_EQ(centre_raw(c), 128);
  c.centre_raw = 300;
  EXPECT_THROW(validate_blade_mapping(c), std::invalid_argument);
  c = {};
  c.max_raw = 256;
  EXPECT_THROW(validate_blade_mapping(c), std::invalid_argument);
  c = {};
  c.full_scale_um = 0;
  EXPECT_THROW(validate_blade_mapping(c), std::invalid_argument);
  EXPECT_NO_THROW(validate_blade_mapping(LateroBladeMapping{}));
}

}  // namespace
}  // namespace tactile::display
