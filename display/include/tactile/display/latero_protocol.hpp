#pragma once
// The Latero's UDP protocol (Tactile Labs, open as OpenLatero): one request datagram per frame,
// one reply per request. Byte layout in docs/protocol.md ("Latero"). Plain data and pure
// functions only; the sockets are in latero_transport.hpp and latero_emulator.hpp.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tactile::display {

inline constexpr std::uint16_t kLateroDefaultPort = 8900;
inline constexpr std::uint8_t kLateroMagic = 0xCA;
inline constexpr std::uint8_t kLateroVersion = 0x11;  // protocol version 1, revision 1
// Clients always send (and the controller answers with) datagrams of this size; the fields
// of every packet type fit in fewer bytes and the rest is padding.
inline constexpr std::size_t kLateroDatagramBytes = 100;
inline constexpr std::size_t kLateroHeaderBytes = 5;
inline constexpr int kLateroBlades = 64;  // 8 x 8, row-major (y * 8 + x)

enum class LateroPacketType : std::uint8_t {
  full = 0x01,  // blades, digital outputs and DACs
  io = 0x02,    // digital outputs and DACs only
  raw = 0x03,   // register read or write
  full_reply_page0 = 0x81,
  full_reply_page1 = 0x82,
  raw_reply = 0x83,
};

// Bytes each packet type needs (header included); shorter datagrams are malformed.
inline constexpr std::size_t kLateroFullRequestBytes = 79;  // 5 + 2 + 8 + 64
inline constexpr std::size_t kLateroIoRequestBytes = 15;    // 5 + 2 + 8
inline constexpr std::size_t kLateroRawBytes = 10;          // 5 + 1 + 2 + 2
inline constexpr std::size_t kLateroFullReplyBytes = 35;    // 5 + 2 + 2 + 2 + 16 + 8

// RAW command byte: read or write, to the controller or to the IO board.
inline constexpr std::uint8_t kLateroRawRead = 0x01;
inline constexpr std::uint8_t kLateroRawWrite = 0x02;
inline constexpr std::uint8_t kLateroRawController = 0x10;
inline constexpr std::uint8_t kLateroRawIoBoard = 0x20;

// Controller status word of a reply.
inline constexpr std::uint16_t kLateroStatusActivePage = 0x0001;
inline constexpr std::uint16_t kLateroStatusHvPoweredOff = 0x0002;
inline constexpr std::uint16_t kLateroStatusHvActive = 0x0004;
// Buttons in dio_in, active-low (the bit is 0 while the button is held).
inline constexpr std::uint16_t kLateroButton0Mask = 0x0040;  // left
inline constexpr std::uint16_t kLateroButton1Mask = 0x0020;  // right

// A request (FULL, IO or RAW); fields a type does not carry are ignored when encoding.
struct LateroRequest {
  LateroPacketType type = LateroPacketType::full;
  std::uint16_t sequence = 0;  // not maintained by OpenLatero's clients; never validated
  std::uint16_t dio_out = 0;
  std::array<std::uint16_t, 4> dac{};
  std::array<std::uint8_t, kLateroBlades> blade{};
  std::uint8_t raw_command = 0;
  std::uint16_t raw_address = 0;
  std::uint16_t raw_data = 0;
};

// A reply: FULL reply (0x81/0x82) to FULL and IO requests, RAW reply (0x83) to RAW requests.
struct LateroReply {
  LateroPacketType type = LateroPacketType::full_reply_page0;
  std::uint16_t sequence = 0;
  std::uint16_t dio_in = 0;
  std::uint16_t controller_status = 0;
  std::uint16_t io_status = 0;  // 0: no IO board answered
  std::array<std::uint32_t, 4> encoder{};
  std::array<std::uint16_t, 4> adc{};
  std::uint8_t raw_command = 0;
  std::uint16_t raw_address = 0;
  std::uint16_t raw_data = 0;
};

enum class LateroPacketError : std::uint8_t {
  none = 0,
  too_short,  // fewer bytes than the packet type's fields
  oversized,  // more than kLateroDatagramBytes
  bad_magic,
  bad_version,
  bad_type,  // unknown type, or a reply where a request belongs (and the other way round)
};
inline constexpr int kLateroPacketErrorCount = 6;

// Short fixed name, e.g. "bad_magic" (counters and messages).
const char* latero_error_name(LateroPacketError error);
// The wrong part of a malformed packet as a person says it, e.g. "wrong magic"; "undecodable"
// for none (reports that count malformed packets by error).
const char* latero_error_words(LateroPacketError error);

template <class T>
struct LateroDecoded {
  std::optional<T> packet;  // set when error == none
  LateroPacketError error = LateroPacketError::none;
};

// Always kLateroDatagramBytes long, padding zero.
std::vector<std::uint8_t> encode_latero_request(const LateroRequest& request);
std::vector<std::uint8_t> encode_latero_reply(const LateroReply& reply);
LateroDecoded<LateroRequest> decode_latero_request(std::span<const std::uint8_t> bytes);
LateroDecoded<LateroReply> decode_latero_reply(std::span<const std::uint8_t> bytes);

// Decoded views of the status words.
struct LateroControllerStatus {
  int fpga_version = 0;
  int fpga_revision = 0;
  bool high_voltage_powered_off = false;
  bool high_voltage_active = false;
  int active_page = 0;
};
LateroControllerStatus decode_controller_status(std::uint16_t word);
std::uint16_t encode_controller_status(const LateroControllerStatus& status);
// "FPGA 1.2, high voltage active, page 0" and "IO board FPGA 1.0" / "no IO board".
std::string describe_controller_status(std::uint16_t word);
std::string describe_io_status(std::uint16_t word);

// Blade deflection to the raw byte the controller takes. OpenLatero's C library maps a
// normalised deflection v in [-1, 1] to raw = (0.5 - 0.5 v) * 150, and its C++ TactileDisplay
// passes it -v "so that -1 is to the left and +1 is to the right": a deflection towards +x
// (the layout's columns, to the right) raises the raw value. Centre 75, 75 raw units per unit
// of v. OpenLatero itself doubts both numbers (it parks blades at 0x80 when it opens the
// device, and marks 150 as unverified), so every number is a field here:
//   raw = clamp(round(centre_raw + raw_per_unit * deflection_um / full_scale_um), 0, max_raw)
struct LateroBladeMapping {
  double centre_raw = 75;
  double raw_per_unit = 75;    // raw units per unit of v (negative: +x lowers the raw value)
  double max_raw = 150;        // raw values are clamped to [0, max_raw]
  double full_scale_um = 100;  // deflection at v = 1 (the latero layout's range)
};
// Throws std::invalid_argument naming the inconsistent field (centre outside [0, max_raw],
// max_raw above 255, non-positive scale, non-finite values).
void validate_blade_mapping(const LateroBladeMapping& mapping);
// Rounds to the nearest raw value and clamps to [0, max_raw].
std::uint8_t blade_raw(double deflection_um, const LateroBladeMapping& mapping);
double blade_deflection_um(std::uint8_t raw, const LateroBladeMapping& mapping);
std::uint8_t centre_raw(const LateroBladeMapping& mapping);

}  // namespace tactile::display
