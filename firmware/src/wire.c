/* Frame encoding and decoding; see tactile_fw/wire.h for the layout. */
#include "tactile_fw/wire.h"

#include "le_bytes.h"

const char* tfw_result_name(tfw_result result) {
  switch (result) {
    case TFW_OK:
      return "ok";
    case TFW_ERR_BAD_LENGTH:
      return "bad_length";
    case TFW_ERR_BAD_MAGIC:
      return "bad_magic";
    case TFW_ERR_BAD_VERSION:
      return "bad_version";
    case TFW_ERR_BAD_COUNT:
      return "bad_count";
    case TFW_ERR_BAD_CHECKSUM:
      return "bad_checksum";
    case TFW_ERR_BAD_SEQUENCE:
      return "bad_sequence";
    case TFW_ERR_FIFO_FULL:
      return "fifo_full";
    case TFW_ERR_BUFFER_TOO_SMALL:
      return "buffer_too_small";
    case TFW_ERR_NOT_STARTED:
      return "not_started";
  }
  return "unknown";
}

uint32_t tfw_crc32(const uint8_t* data, size_t len) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < len; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) {
      /* Branch-free: the mask is all ones when the low bit is set. */
      const uint32_t mask = (uint32_t)(-(int32_t)(crc & 1u));
      crc = (crc >> 1) ^ (0xEDB88320u & mask);
    }
  }
  return ~crc;
}

tfw_result tfw_encode_frame(uint32_t sequence, uint8_t flags, const int16_t* deflection,
                            uint16_t contactor_count, uint8_t* out, size_t out_capacity,
                            size_t* out_len) {
  if (contactor_count == 0 || contactor_count > TFW_MAX_CONTACTORS) return TFW_ERR_BAD_COUNT;
  if ((flags & ~TFW_KNOWN_FLAGS) != 0) return TFW_ERR_BAD_VERSION;
  const size_t total = TFW_FRAME_BYTES(contactor_count);
  if (out_capacity < total) return TFW_ERR_BUFFER_TOO_SMALL;
  tfw_put_u32(out, TFW_MAGIC);
  out[4] = (uint8_t)TFW_PROTOCOL_VERSION;
  out[5] = flags;
  tfw_put_u16(out + 6, contactor_count);
  tfw_put_u32(out + 8, sequence);
  for (uint16_t i = 0; i < contactor_count; ++i) {
    tfw_put_u16(out + TFW_HEADER_BYTES + 2u * i, (uint16_t)deflection[i]);
  }
  const size_t body = TFW_HEADER_BYTES + 2u * (size_t)contactor_count;
  tfw_put_u32(out + body, tfw_crc32(out, body));
  *out_len = total;
  return TFW_OK;
}

tfw_result tfw_decode_frame(const uint8_t* bytes, size_t len, tfw_frame_header* header,
                            int16_t* deflection, size_t deflection_capacity) {
  if (len < TFW_FRAME_BYTES(0)) return TFW_ERR_BAD_LENGTH;
  if (tfw_get_u32(bytes) != TFW_MAGIC) return TFW_ERR_BAD_MAGIC;
  const uint8_t version = bytes[4];
  const uint8_t flags = bytes[5];
  if (version != TFW_PROTOCOL_VERSION || (flags & ~TFW_KNOWN_FLAGS) != 0) {
    return TFW_ERR_BAD_VERSION;
  }
  const uint16_t count = tfw_get_u16(bytes + 6);
  /* Length before count: a truncated frame is reported as such even if its count is large. */
  if (len != TFW_FRAME_BYTES(count)) return TFW_ERR_BAD_LENGTH;
  if (count == 0 || count > TFW_MAX_CONTACTORS) return TFW_ERR_BAD_COUNT;
  const size_t body = TFW_HEADER_BYTES + 2u * (size_t)count;
  if (tfw_get_u32(bytes + body) != tfw_crc32(bytes, body)) return TFW_ERR_BAD_CHECKSUM;
  if (deflection != NULL && count > deflection_capacity) return TFW_ERR_BUFFER_TOO_SMALL;
  header->version = version;
  header->flags = flags;
  header->contactor_count = count;
  header->sequence = tfw_get_u32(bytes + 8);
  if (deflection == NULL) return TFW_OK;
  for (uint16_t i = 0; i < count; ++i) {
    deflection[i] = tfw_get_i16(bytes + TFW_HEADER_BYTES + 2u * i);
  }
  return TFW_OK;
}

int tfw_sequence_is_newer(uint32_t sequence, uint32_t previous) {
  const uint32_t diff = sequence - previous;
  return diff != 0u && diff < 0x80000000u;
}
