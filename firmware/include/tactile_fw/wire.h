#ifndef TACTILE_FW_WIRE_H
#define TACTILE_FW_WIRE_H
/*
 * The frame wire format shared by the firmware and the host (display/).
 *
 * One frame = one set of contactor deflections, all fields little-endian:
 *
 *   offset  size  field
 *   0       4     magic            0x4D544354 (bytes "TCTM")
 *   4       1     version          TFW_PROTOCOL_VERSION
 *   5       1     flags            bit 0: end of stream (TFW_FLAG_END_OF_STREAM); others 0
 *   6       2     contactor_count  n, 1..TFW_MAX_CONTACTORS
 *   8       4     sequence         u32, strictly increasing (modulo 2^32) within a stream
 *   12      2*n   deflection       i16 per contactor, row-major, unit 0.1 um (TFW_UNITS_PER_UM)
 *   12+2n   4     crc32            CRC-32 (IEEE 802.3, reflected, poly 0xEDB88320) of bytes
 *                                  0 .. 12+2n-1
 *
 * Total size TFW_FRAME_BYTES(n) = 16 + 2n (216 bytes for the 10 x 10 STReSS array).
 * 0.1 um steps resolve far below what skin can feel while i16 still spans +-3.2 mm, so no
 * display of the STReSS family can saturate the encoding.
 *
 * The decoder is stateless; sequence ordering is checked by the receiver with
 * tfw_sequence_is_newer() because it needs the previous sequence number.
 */
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TFW_MAGIC 0x4D544354u
#define TFW_PROTOCOL_VERSION 1u
#define TFW_FLAG_END_OF_STREAM 0x01u
#define TFW_KNOWN_FLAGS (TFW_FLAG_END_OF_STREAM)

/* Deflection units on the wire: 10 units per micrometre. */
#define TFW_UNITS_PER_UM 10

#ifndef TFW_MAX_CONTACTORS
/* Large enough for every display of the STReSS family (100) with room to grow. */
#define TFW_MAX_CONTACTORS 256u
#endif

#define TFW_HEADER_BYTES 12u
#define TFW_CRC_BYTES 4u
#define TFW_FRAME_BYTES(n) (TFW_HEADER_BYTES + 2u * (size_t)(n) + TFW_CRC_BYTES)
#define TFW_MAX_FRAME_BYTES TFW_FRAME_BYTES(TFW_MAX_CONTACTORS)

/* Result of encoding, decoding or accepting a frame. Every rejection has its own code so
 * the device can count malformed frames by reason. */
typedef enum {
  TFW_OK = 0,
  TFW_ERR_BAD_LENGTH = 1,       /* shorter than a header, or length != 16 + 2n */
  TFW_ERR_BAD_MAGIC = 2,        /* first four bytes are not "TCTM" */
  TFW_ERR_BAD_VERSION = 3,      /* protocol version or flags this firmware does not know */
  TFW_ERR_BAD_COUNT = 4,        /* contactor count 0, too large, or not the device's */
  TFW_ERR_BAD_CHECKSUM = 5,     /* CRC-32 mismatch */
  TFW_ERR_BAD_SEQUENCE = 6,     /* repeated or out-of-order sequence number */
  TFW_ERR_FIFO_FULL = 7,        /* well-formed but no room: the host should have waited */
  TFW_ERR_BUFFER_TOO_SMALL = 8, /* caller's buffer cannot hold the frame (encode/decode) */
  TFW_ERR_NOT_STARTED = 9       /* device stopped: frames are refused until started */
} tfw_result;

#define TFW_RESULT_COUNT 10

typedef struct {
  uint8_t version;
  uint8_t flags;
  uint16_t contactor_count;
  uint32_t sequence;
} tfw_frame_header;

/* Short fixed name of a result code, e.g. "bad_checksum" (for logs and host messages). */
const char* tfw_result_name(tfw_result result);

/* CRC-32 (IEEE) of `len` bytes, bitwise so that it needs no table in flash or RAM. */
uint32_t tfw_crc32(const uint8_t* data, size_t len);

/* Encodes a frame into `out` (capacity `out_capacity` bytes); on success stores the size in
 * `*out_len`. Fails with TFW_ERR_BAD_COUNT for n == 0 or n > TFW_MAX_CONTACTORS. */
tfw_result tfw_encode_frame(uint32_t sequence, uint8_t flags, const int16_t* deflection,
                            uint16_t contactor_count, uint8_t* out, size_t out_capacity,
                            size_t* out_len);

/* Decodes and verifies a frame: length, magic, version/flags, count (at most
 * `deflection_capacity`), checksum. Deflections are written only when the whole frame is
 * valid, so a rejected frame never leaves partial data behind. With `deflection` NULL the
 * frame is only verified (used to classify a frame that has nowhere to go). */
tfw_result tfw_decode_frame(const uint8_t* bytes, size_t len, tfw_frame_header* header,
                            int16_t* deflection, size_t deflection_capacity);

/* True when `sequence` comes after `previous` in wrap-around order (serial number
 * arithmetic, like TCP): a repeated or older number is not newer. */
int tfw_sequence_is_newer(uint32_t sequence, uint32_t previous);

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_WIRE_H */
