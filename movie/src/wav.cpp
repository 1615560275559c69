// Multichannel float WAV export.

#include "tactile/movie/wav.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tactile/common/atomic_write.hpp"
#include "tactile/movie/hjif.hpp"

namespace tactile::movie {
namespace {

void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xFFU);
  out += static_cast<char>((v >> 8) & 0xFFU);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xFFFFU);
  put16(out, v >> 16);
}

// KSDATAFORMAT_SUBTYPE_IEEE_FLOAT: format tag 3 in the base GUID of WAVE_FORMAT_EXTENSIBLE.
constexpr std::array<unsigned char, 16> kFloatSubformat = {
    0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x10, 0x00, 0x80, 0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};

}  // namespace

double write_wav(const TactileMovie& movie, const std::filesystem::path& path) {
  validate_movie(movie);
  if (movie.rate_hz != std::round(movie.rate_hz)) {
    throw std::invalid_argument(fmt::format(
        "WAV: rate {:g} Hz is not a whole number of hertz (a WAV header holds an integer rate)",
        movie.rate_hz));
  }
  const auto channels = static_cast<std::uint64_t>(movie.layout.contactor_count());
  if (channels > 0xFFFF) {
    throw std::invalid_argument(fmt::format(
        "WAV: {} contactors is out of range: a WAV file holds at most 65535 channels", channels));
  }
  const std::uint64_t data_bytes = channels * 4 * static_cast<std::uint64_t>(movie.frame_count);
  if (data_bytes > kWavMaxDataBytes) {
    throw std::invalid_argument(fmt::format(
        "WAV: {} frames x {} channels take {} bytes, more than the {} a WAV file can hold",
        movie.frame_count, channels, data_bytes, kWavMaxDataBytes));
  }
  const double scale = full_scale_um(movie);
  const auto rate = static_cast<std::uint32_t>(movie.rate_hz);
  const auto block = static_cast<std::uint32_t>(channels * 4);

  std::string head;
  head += "RIFF";
  put32(head, static_cast<std::uint32_t>(4 + (8 + 40) + (8 + 4) + 8 + data_bytes));
  head += "WAVE";
  head += "fmt ";
  put32(head, 40);
  put16(head, 0xFFFE);  // WAVE_FORMAT_EXTENSIBLE: required beyond two channels
  put16(head, static_cast<std::uint32_t>(channels));
  put32(head, rate);
  put32(head, rate * block);
  put16(head, block);
  put16(head, 32);
  put16(head, 22);  // size of the extension
  put16(head, 32);  // valid bits per sample
  put32(head, 0);   // channel mask: no loudspeaker positions, contactors are not speakers
  head.append(reinterpret_cast<const char*>(kFloatSubformat.data()), kFloatSubformat.size());
  head += "fact";  // required for formats other than PCM
  put32(head, 4);
  put32(head, static_cast<std::uint32_t>(movie.frame_count));
  head += "data";
  put32(head, static_cast<std::uint32_t>(data_bytes));

  AtomicFile file(path);
  file.write(head);
  std::string block_bytes;
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    for (const float v : movie.frame(f)) {
      const auto sample = static_cast<float>(v / scale);
      std::uint32_t bits = 0;
      std::memcpy(&bits, &sample, sizeof bits);
      put32(block_bytes, bits);
    }
    if (block_bytes.size() >= (1U << 20)) {
      file.write(block_bytes);
      block_bytes.clear();
    }
  }
  file.write(block_bytes);
  file.commit();
  return scale;
}

}  // namespace tactile::movie
