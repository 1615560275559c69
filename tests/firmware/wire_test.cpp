// Frame encoding/decoding: round trip, checksum reference value and every rejection kind.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "tactile_fw/wire.h"

namespace {

std::vector<std::uint8_t> encode(std::uint32_t seq, const std::vector<std::int16_t>& values,
                                 std::uint8_t flags = 0) {
  std::vector<std::uint8_t> out(TFW_MAX_FRAME_BYTES);
  std::size_t len = 0;
  EXPECT_EQ(tfw_encode_frame(seq, flags, values.data(), static_cast<std::uint16_t>(values.size()),
                             out.data(), out.size(), &len),
            TFW_OK);
  out.resize(len);
  return out;
}

TEST(Wire, Crc32MatchesTheStandardCheckValue) {
  // "123456789" -> 0xCBF43926 is the published check value of CRC-32/ISO-HDLC.
  const char* text = "123456789";
  EXPECT_EQ(tfw_crc32(reinterpret_cast<const std::uint8_t*>(text), 9), 0xCBF43926u);
}

TEST(Wire, LayoutIsLittleEndianAsDocumented) {
  const auto bytes = encode(0x01020304u, {-2, 300});
  ASSERT_EQ(bytes.size(), 16u + 4u);
  EXPECT_EQ(std::memcmp(bytes.data(), "TCTM", 4), 0);
  EXPECT_EQ(bytes[4], TFW_PROTOCOL_VERSION);
  EXPECT_EQ(bytes[6], 2);
  EXPECT_EQ(bytes[7], 0);
  EXPECT_EQ(bytes[8], 0x04);
  EXPECT_EQ(bytes[11], 0x01);
  EXPECT_EQ(bytes[12], 0xFE);  // -2 as two's complement
  EXPECT_EQ(bytes[13], 0xFF);
  EXPECT_EQ(bytes[14], 300 & 0xFF);
  EXPECT_EQ(bytes[15], 300 >> 8);
}

TEST(Wire, RoundTripRandomFrames) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(-32768, 32767);
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint16_t n = static_cast<std::uint16_t>(1 + rng() % TFW_MAX_CONTACTORS);
    std::vector<std::int16_t> values(n);
    for (auto& v : values) v = static_cast<std::int16_t>(value(rng));
    const std::uint32_t seq = static_cast<std::uint32_t>(rng());
    const auto bytes = encode(seq, values, trial % 2 ? TFW_FLAG_END_OF_STREAM : 0);
    ASSERT_EQ(bytes.size(), TFW_FRAME_BYTES(n));
    tfw_frame_header h{};
    std::vector<std::int16_t> back(TFW_MAX_CONTACTORS);
    ASSERT_EQ(tfw_decode_frame(bytes.data(), bytes.size(), &h, back.data(), back.size()), TFW_OK);
    EXPECT_EQ(h.sequence, seq);
    EXPECT_EQ(h.contactor_count, n);
    EXPECT_EQ(h.flags, trial % 2 ? TFW_FLAG_END_OF_STREAM : 0);
    back.resize(n);
    EXPECT_EQ(back, values);
  }
}

tfw_result decode(const std::vector<std::uint8_t>& bytes) {
  tfw_frame_header h{};
  std::vector<std::int16_t> out(TFW_MAX_CONTACTORS, 1234);
  const tfw_result r = tfw_decode_frame(bytes.data(), bytes.size(), &h, out.data(), out.size());
  if (r != TFW_OK) {
    // A rejected frame leaves no partial data behind.
    for (auto v : out) EXPECT_EQ(v, 1234);
  }
  return r;
}

// Rewrites the checksum so that a test can corrupt a field without tripping the CRC first.
void fix_crc(std::vector<std::uint8_t>& b) {
  const std::size_t body = b.size() - 4;
  const std::uint32_t crc = tfw_crc32(b.data(), body);
  for (int i = 0; i < 4; ++i) b[body + i] = static_cast<std::uint8_t>(crc >> (8 * i));
}

TEST(Wire, EachMalformationHasItsOwnCode) {
  const std::vector<std::int16_t> values(100, 55);
  const auto good = encode(5, values);
  EXPECT_EQ(decode(good), TFW_OK);

  const std::vector<std::uint8_t> truncated(good.begin(), good.end() - 1);
  EXPECT_EQ(decode(truncated), TFW_ERR_BAD_LENGTH);
  EXPECT_EQ(decode({good.begin(), good.begin() + 10}), TFW_ERR_BAD_LENGTH);
  auto longer = good;
  longer.push_back(0);
  EXPECT_EQ(decode(longer), TFW_ERR_BAD_LENGTH);

  auto magic = good;
  magic[0] = 'X';
  EXPECT_EQ(decode(magic), TFW_ERR_BAD_MAGIC);

  auto version = good;
  version[4] = 99;
  fix_crc(version);
  EXPECT_EQ(decode(version), TFW_ERR_BAD_VERSION);
  auto flags = good;
  flags[5] = 0x80;
  fix_crc(flags);
  EXPECT_EQ(decode(flags), TFW_ERR_BAD_VERSION);

  // A count that disagrees with the length is a length error; a zero count with a matching
  // length is a count error.
  auto count = good;
  count[6] = 99;
  fix_crc(count);
  EXPECT_EQ(decode(count), TFW_ERR_BAD_LENGTH);
  std::vector<std::uint8_t> zero(good.begin(), good.begin() + 12);
  zero[6] = 0;
  zero[7] = 0;
  zero.resize(16);
  fix_crc(zero);
  EXPECT_EQ(decode(zero), TFW_ERR_BAD_COUNT);

  for (std::size_t i : {std::size_t{8}, std::size_t{12}, std::size_t{100}, good.size() - 1}) {
    auto flipped = good;
    flipped[i] ^= 0x10;
    EXPECT_EQ(decode(flipped), TFW_ERR_BAD_CHECKSUM) << "byte " << i;
  }
}

TEST(Wire, EncodeRefusesBadInput) {
  std::vector<std::uint8_t> out(TFW_MAX_FRAME_BYTES + 10);
  std::size_t len = 0;
  std::vector<std::int16_t> v(TFW_MAX_CONTACTORS + 1);
  EXPECT_EQ(tfw_encode_frame(0, 0, v.data(), 0, out.data(), out.size(), &len), TFW_ERR_BAD_COUNT);
  EXPECT_EQ(tfw_encode_frame(0, 0, v.data(), TFW_MAX_CONTACTORS + 1, out.data(), out.size(), &len),
            TFW_ERR_BAD_COUNT);
  EXPECT_EQ(tfw_encode_frame(0, 0, v.data(), 10, out.data(), TFW_FRAME_BYTES(10) - 1, &len),
            TFW_ERR_BUFFER_TOO_SMALL);
}

TEST(Wire, SequenceOrderWrapsAround) {
  EXPECT_TRUE(tfw_sequence_is_newer(1, 0));
  EXPECT_TRUE(tfw_sequence_is_newer(10, 3));
  EXPECT_FALSE(tfw_sequence_is_newer(3, 3));
  EXPECT_FALSE(tfw_sequence_is_newer(2, 3));
  EXPECT_TRUE(tfw_sequence_is_newer(0, 0xFFFFFFFFu));
  EXPECT_FALSE(tfw_sequence_is_newer(0xFFFFFFFFu, 0));
}

}  // namespace
