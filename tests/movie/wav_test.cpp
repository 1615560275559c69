// Multichannel WAV export: the file is parsed here byte by byte, independently of the writer.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/movie/wav.hpp"
#include "test_movies.hpp"

namespace tactile::movie {
namespace {

std::uint32_t u32(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}
std::uint32_t u16(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8;
}

TEST(Wav, HeaderAndSamplesAreAFloatWaveOneChannelPerContactor) {
  test::TempDir dir;
  // 12 um peak on a +-50 um layout: the full scale is the layout's, 50 um.
  const TactileMovie m = testing::sine_movie(stress_layout(), 700, 33, 12.0);
  const double scale = write_wav(m, dir / "m.wav");
  EXPECT_DOUBLE_EQ(scale, 50.0);
  std::ifstream in(dir / "m.wav", std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(b.size(), 12U);
  EXPECT_EQ(b.substr(0, 4), "RIFF");
  EXPECT_EQ(u32(b, 4), b.size() - 8);
  EXPECT_EQ(b.substr(8, 4), "WAVE");
  // Walk the chunks as any reader does.
  std::size_t at = 12, data_at = 0, data_size = 0;
  bool fmt_seen = false, fact_seen = false;
  while (at + 8 <= b.size()) {
    const std::string id = b.substr(at, 4);
    const std::uint32_t size = u32(b, at + 4);
    const std::size_t body = at + 8;
    if (id == "fmt ") {
      fmt_seen = true;
      ASSERT_EQ(size, 40U);
      EXPECT_EQ(u16(b, body), 0xFFFEU);             // WAVE_FORMAT_EXTENSIBLE
      EXPECT_EQ(u16(b, body + 2), 100U);            // channels
      EXPECT_EQ(u32(b, body + 4), 700U);            // samples per second
      EXPECT_EQ(u32(b, body + 8), 700U * 100 * 4);  // bytes per second
      EXPECT_EQ(u16(b, body + 12), 400U);           // block align
      EXPECT_EQ(u16(b, body + 14), 32U);            // bits per sample
      EXPECT_EQ(u16(b, body + 16), 22U);            // extension size
      EXPECT_EQ(u16(b, body + 18), 32U);            // valid bits
      EXPECT_EQ(u32(b, body + 24), 3U);             // sub-format: IEEE float
      EXPECT_EQ(u32(b, body + 28), 0x00100000U);    // ... in the base GUID
      EXPECT_EQ(u32(b, body + 32), 0xAA000080U);
      EXPECT_EQ(u32(b, body + 36), 0x719B3800U);
    } else if (id == "fact") {
      fact_seen = true;
      EXPECT_EQ(u32(b, body), 33U);
    } else if (id == "data") {
      data_at = body;
      data_size = size;
    }
    at = body + size + (size & 1U);
  }
  EXPECT_TRUE(fmt_seen);
  EXPECT_TRUE(fact_seen);
  ASSERT_EQ(data_size, 33U * 100 * 4);
  ASSERT_EQ(data_at + data_size, b.size());
  for (std::int32_t f = 0; f < 33; ++f) {
    for (std::int32_t k = 0; k < 100; ++k) {
      const std::uint32_t bits = u32(b, data_at + 4 * (static_cast<std::size_t>(f) * 100 + k));
      float v = 0;
      std::memcpy(&v, &bits, sizeof v);
      EXPECT_NEAR(v, m.frame(f)[k] / 50.0, 1e-7) << f << " " << k;
    }
  }
}

TEST(Wav, FullScaleGrowsWithAMovieBeyondItsLayout) {
  test::TempDir dir;
  const TactileMovie m = testing::sine_movie(stress_layout(), 700, 50, 80.0);
  const double scale = write_wav(m, dir / "m.wav");
  EXPECT_GT(scale, 79.0);
  EXPECT_LE(scale, 80.0);
}

TEST(Wav, RefusesARateThatIsNotWholeHertz) {
  test::TempDir dir;
  const TactileMovie m = testing::sine_movie(stress_layout(), 700.5, 5, 1.0);
  EXPECT_THAT([&] { write_wav(m, dir / "m.wav"); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("700.5 Hz is not a whole number of hertz")));
  EXPECT_FALSE(std::filesystem::exists(dir / "m.wav"));
}

}  // namespace
}  // namespace tactile::movie
