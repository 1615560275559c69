#ifndef TACTILE_FW_LE_BYTES_H
#define TACTILE_FW_LE_BYTES_H
/* Little-endian field access for the wire, control and USB encodings (private to the firmware
 * sources). Byte by byte, so that neither the CPU's byte order nor alignment matters. */
#include <stdint.h>

static inline void tfw_put_u16(uint8_t* p, uint16_t v) {
  p[0] = (uint8_t)(v & 0xFFu);
  p[1] = (uint8_t)(v >> 8);
}

static inline void tfw_put_u32(uint8_t* p, uint32_t v) {
  tfw_put_u16(p, (uint16_t)(v & 0xFFFFu));
  tfw_put_u16(p + 2, (uint16_t)(v >> 16));
}

static inline uint16_t tfw_get_u16(const uint8_t* p) {
  return (uint16_t)(p[0] | (p[1] << 8));
}

static inline uint32_t tfw_get_u32(const uint8_t* p) {
  return (uint32_t)tfw_get_u16(p) | ((uint32_t)tfw_get_u16(p + 2) << 16);
}

/* Two's complement by arithmetic, because converting an out-of-range value to a signed type is
 * implementation-defined in C11. */
static inline int16_t tfw_get_i16(const uint8_t* p) {
  const int32_t v = (int32_t)tfw_get_u16(p);
  return (int16_t)(v >= 0x8000 ? v - 0x10000 : v);
}

#endif /* TACTILE_FW_LE_BYTES_H */
