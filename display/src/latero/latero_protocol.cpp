// The Latero's packets to and from bytes; layout in docs/protocol.md ("Latero").
#include "tactile/display/latero_protocol.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace tactile::display {
namespace {

// Every multi-byte field is big-endian (network order).
void put16(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v >> 8);
  b[at + 1] = static_cast<std::uint8_t>(v & 0xFF);
}

void put32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  put16(b, at, static_cast<std::uint16_t>(v >> 16));
  put16(b, at + 2, static_cast<std::uint16_t>(v & 0xFFFF));
}

std::uint16_t get16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) {
  return (std::uint32_t{get16(b, at)} << 16) | get16(b, at + 2);
}

// RAW requests and replies share their body: command, address, data.
void put_raw(std::vector<std::uint8_t>& b, std::uint8_t command, std::uint16_t address,
             std::uint16_t data) {
  b[5] = command;
  put16(b, 6, address);
  put16(b, 8, data);
}

template <class Packet>
void get_raw(std::span<const std::uint8_t> b, Packet& p) {
  p.raw_command = b[5];
  p.raw_address = get16(b, 6);
  p.raw_data = get16(b, 8);
}

std::vector<std::uint8_t> header(LateroPacketType type, std::uint16_t sequence) {
  std::vector<std::uint8_t> b(kLateroDatagramBytes, 0);
  b[0] = kLateroMagic;
  b[1] = kLateroVersion;
  b[2] = static_cast<std::uint8_t>(type);
  put16(b, 3, sequence);
  return b;
}

// Bytes a packet of `type` needs, or 0 when `type` does not travel in this direction.
std::size_t needed_bytes(std::uint8_t type, bool request) {
  switch (type) {
    case 0x01:
      return request ? kLateroFullRequestBytes : 0;
    case 0x02:
      return request ? kLateroIoRequestBytes : 0;
    case 0x03:
      return request ? kLateroRawBytes : 0;
    case 0x81:
    case 0x82:
      return request ? 0 : kLateroFullReplyBytes;
    case 0x83:
      return request ? 0 : kLateroRawBytes;
    default:
      return 0;
  }
}

// Writes what every datagram shares and, for `raw_type`, the RAW body; `body` writes the other
// types' fields and returns false for a type that does not travel as a `direction`.
template <class Packet, class Body>
std::vector<std::uint8_t> encode(const Packet& p, LateroPacketType raw_type, const char* direction,
                                 Body body) {
  std::vector<std::uint8_t> b = header(p.type, p.sequence);
  if (p.type == raw_type) {
    put_raw(b, p.raw_command, p.raw_address, p.raw_data);
  } else if (!body(b)) {
    throw std::invalid_argument(
        fmt::format("0x{:02X} is not a Latero {} type", static_cast<int>(p.type), direction));
  }
  return b;
}

// Checks what every datagram shares and reads a RAW body, then lets `body` read the other
// types' fields.
template <class Packet, class Body>
LateroDecoded<Packet> decode(std::span<const std::uint8_t> bytes, bool request,
                             LateroPacketType raw_type, Body body) {
  auto fail = [](LateroPacketError e) { return LateroDecoded<Packet>{std::nullopt, e}; };
  if (bytes.size() > kLateroDatagramBytes) return fail(LateroPacketError::oversized);
  if (bytes.size() < kLateroHeaderBytes) return fail(LateroPacketError::too_short);
  if (bytes[0] != kLateroMagic) return fail(LateroPacketError::bad_magic);
  if (bytes[1] != kLateroVersion) return fail(LateroPacketError::bad_version);
  const std::size_t n = needed_bytes(bytes[2], request);
  if (n == 0) return fail(LateroPacketError::bad_type);
  if (bytes.size() < n) return fail(LateroPacketError::too_short);
  Packet p;
  p.type = static_cast<LateroPacketType>(bytes[2]);
  p.sequence = get16(bytes, 3);
  if (p.type == raw_type) {
    get_raw(bytes, p);
  } else {
    body(p);
  }
  return {p, LateroPacketError::none};
}

// Each error's two spellings side by side, so that a new error cannot get one without the
// other: its fixed name and the wrong part as a person says it.
struct ErrorText {
  LateroPacketError error;
  const char* name;
  const char* words;
};
constexpr std::array<ErrorText, kLateroPacketErrorCount> kErrorTexts = {{
    {LateroPacketError::none, "none", "undecodable"},
    {LateroPacketError::too_short, "too_short", "too short"},
    {LateroPacketError::oversized, "oversized", "oversized"},
    {LateroPacketError::bad_magic, "bad_magic", "wrong magic"},
    {LateroPacketError::bad_version, "bad_version", "wrong protocol version"},
    {LateroPacketError::bad_type, "bad_type", "unknown packet type"},
}};

ErrorText error_text(LateroPacketError error) {
  for (const ErrorText& t : kErrorTexts)
    if (t.error == error) return t;
  return {error, "unknown", "undecodable"};
}

}  // namespace

const char* latero_error_name(LateroPacketError error) {
  return error_text(error).name;
}

const char* latero_error_words(LateroPacketError error) {
  return error_text(error).words;
}

std::vector<std::uint8_t> encode_latero_request(const LateroRequest& r) {
  return encode(r, LateroPacketType::raw, "request", [&](std::vector<std::uint8_t>& b) {
    if (r.type != LateroPacketType::full && r.type != LateroPacketType::io) return false;
    put16(b, 5, r.dio_out);
    for (std::size_t i = 0; i < 4; ++i) put16(b, 7 + 2 * i, r.dac[i]);
    if (r.type == LateroPacketType::full) {
      std::copy(r.blade.begin(), r.blade.end(), b.begin() + 15);
    }
    return true;
  });
}

std::vector<std::uint8_t> encode_latero_reply(const LateroReply& r) {
  return encode(r, LateroPacketType::raw_reply, "reply", [&](std::vector<std::uint8_t>& b) {
    if (r.type != LateroPacketType::full_reply_page0 &&
        r.type != LateroPacketType::full_reply_page1) {
      return false;
    }
    put16(b, 5, r.dio_in);
    put16(b, 7, r.controller_status);
    put16(b, 9, r.io_status);
    for (std::size_t i = 0; i < 4; ++i) put32(b, 11 + 4 * i, r.encoder[i]);
    for (std::size_t i = 0; i < 4; ++i) put16(b, 27 + 2 * i, r.adc[i]);
    return true;
  });
}

LateroDecoded<LateroRequest> decode_latero_request(std::span<const std::uint8_t> bytes) {
  return decode<LateroRequest>(bytes, true, LateroPacketType::raw, [&](LateroRequest& r) {
    r.dio_out = get16(bytes, 5);
    for (std::size_t i = 0; i < 4; ++i) r.dac[i] = get16(bytes, 7 + 2 * i);
    if (r.type == LateroPacketType::full) {
      std::copy_n(bytes.begin() + 15, kLateroBlades, r.blade.begin());
    }
  });
}

LateroDecoded<LateroReply> decode_latero_reply(std::span<const std::uint8_t> bytes) {
  return decode<LateroReply>(bytes, false, LateroPacketType::raw_reply, [&](LateroReply& r) {
    r.dio_in = get16(bytes, 5);
    r.controller_status = get16(bytes, 7);
    r.io_status = get16(bytes, 9);
    for (std::size_t i = 0; i < 4; ++i) r.encoder[i] = get32(bytes, 11 + 4 * i);
    for (std::size_t i = 0; i < 4; ++i) r.adc[i] = get16(bytes, 27 + 2 * i);
  });
}

LateroControllerStatus decode_controller_status(std::uint16_t word) {
  LateroControllerStatus s;
  s.fpga_version = (word >> 8) & 0x0F;
  s.fpga_revision = (word >> 4) & 0x0F;
  s.high_voltage_powered_off = (word & kLateroStatusHvPoweredOff) != 0;
  s.high_voltage_active = (word & kLateroStatusHvActive) != 0;
  s.active_page = word & kLateroStatusActivePage;
  return s;
}

std::uint16_t encode_controller_status(const LateroControllerStatus& s) {
  auto word = static_cast<std::uint16_t>(((s.fpga_version & 0x0F) << 8) |
                                         ((s.fpga_revision & 0x0F) << 4) | (s.active_page & 1));
  if (s.high_voltage_powered_off) word |= kLateroStatusHvPoweredOff;
  if (s.high_voltage_active) word |= kLateroStatusHvActive;
  return word;
}

std::string describe_controller_status(std::uint16_t word) {
  const LateroControllerStatus s = decode_controller_status(word);
  std::string hv = s.high_voltage_active ? "active" : "";
  if (s.high_voltage_powered_off) hv += hv.empty() ? "powered off" : " and powered off";
  if (hv.empty()) hv = "neither active nor powered off";
  return fmt::format("controller FPGA {}.{}, high voltage {}, page {}", s.fpga_version,
                     s.fpga_revision, hv, s.active_page);
}

std::string describe_io_status(std::uint16_t word) {
  if (word == 0) return "no IO board (status 0: unplugged or not powered)";
  return fmt::format("IO board FPGA {}.{}, encoder error mask 0x{:X}", (word >> 8) & 0x0F,
                     (word >> 4) & 0x0F, word & 0x0F);
}

void validate_blade_mapping(const LateroBladeMapping& m) {
  for (const double v : {m.centre_raw, m.raw_per_unit, m.max_raw, m.full_scale_um}) {
    if (!std::isfinite(v))
      throw std::invalid_argument("Latero blade mapping has a non-finite value");
  }
  if (m.max_raw <= 0 || m.max_raw > 255) {
    throw std::invalid_argument(
        fmt::format("Latero blade mapping: max_raw {} is outside 1..255 (one byte)", m.max_raw));
  }
  if (m.centre_raw < 0 || m.centre_raw > m.max_raw) {
    throw std::invalid_argument(fmt::format(
        "Latero blade mapping: centre_raw {} is outside [0, max_raw {}]", m.centre_raw, m.max_raw));
  }
  if (m.raw_per_unit == 0) {
    throw std::invalid_argument("Latero blade mapping: raw_per_unit must not be 0");
  }
  if (m.full_scale_um <= 0) {
    throw std::invalid_argument(
        fmt::format("Latero blade mapping: full_scale_um {} must be positive", m.full_scale_um));
  }
}

std::uint8_t blade_raw(double deflection_um, const LateroBladeMapping& m) {
  if (!std::isfinite(deflection_um)) return centre_raw(m);
  const double raw = std::round(m.centre_raw + m.raw_per_unit * deflection_um / m.full_scale_um);
  return static_cast<std::uint8_t>(std::clamp(raw, 0.0, std::floor(m.max_raw)));
}

double blade_deflection_um(std::uint8_t raw, const LateroBladeMapping& m) {
  return (raw - m.centre_raw) / m.raw_per_unit * m.full_scale_um;
}

std::uint8_t centre_raw(const LateroBladeMapping& m) {
  return static_cast<std::uint8_t>(std::clamp(std::round(m.centre_raw), 0.0, 255.0));
}

}  // namespace tactile::display
