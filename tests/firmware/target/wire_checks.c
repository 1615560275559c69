/* Frame wire format: CRC check value, byte layout, every malformation, sequence order. */
#include <string.h>

#include "check.h"
#include "tactile_fw/wire.h"

void wire_checks(tfw_check_run* run) {
  /* The CRC-32 catalogue check value of "123456789" (IEEE 802.3). */
  CHECK(run, tfw_crc32((const uint8_t*)"123456789", 9) == 0xCBF43926u);

  const int16_t values[3] = {1, -2, 300};
  uint8_t frame[TFW_FRAME_BYTES(3)];
  size_t len = 0;
  CHECK(run, tfw_encode_frame(0x01020304u, 0, values, 3, frame, sizeof frame, &len) == TFW_OK);
  CHECK(run, len == 22u);
  /* Little-endian "TCTM" magic, then version, flags, count, sequence, deflections. */
  CHECK(run, frame[0] == 'T' && frame[1] == 'C' && frame[2] == 'T' && frame[3] == 'M');
  CHECK(run, frame[4] == 1 && frame[5] == 0 && frame[6] == 3 && frame[7] == 0);
  CHECK(run, frame[8] == 4 && frame[9] == 3 && frame[10] == 2 && frame[11] == 1);
  CHECK(run, frame[14] == 0xFE && frame[15] == 0xFF); /* -2 in two's complement */
  CHECK(run, frame[16] == 0x2C && frame[17] == 0x01); /* 300 = 0x012C */
  const uint32_t crc = tfw_crc32(frame, 18);
  CHECK(run, frame[18] == (crc & 0xFFu) && frame[21] == (crc >> 24));

  tfw_frame_header h;
  int16_t out[3] = {0, 0, 0};
  CHECK(run, tfw_decode_frame(frame, len, &h, out, 3) == TFW_OK);
  CHECK(run, h.sequence == 0x01020304u && h.contactor_count == 3);
  CHECK(run, out[0] == 1 && out[1] == -2 && out[2] == 300);

  uint8_t bad[sizeof frame];
  memcpy(bad, frame, sizeof frame);
  CHECK(run, tfw_decode_frame(bad, len - 1, &h, out, 3) == TFW_ERR_BAD_LENGTH);
  CHECK(run, tfw_decode_frame(bad, 5, &h, out, 3) == TFW_ERR_BAD_LENGTH);
  bad[0] = 'X';
  CHECK(run, tfw_decode_frame(bad, len, &h, out, 3) == TFW_ERR_BAD_MAGIC);
  memcpy(bad, frame, sizeof frame);
  bad[4] = 2;
  CHECK(run, tfw_decode_frame(bad, len, &h, out, 3) == TFW_ERR_BAD_VERSION);
  memcpy(bad, frame, sizeof frame);
  bad[5] = 0x80; /* unknown flag */
  CHECK(run, tfw_decode_frame(bad, len, &h, out, 3) == TFW_ERR_BAD_VERSION);
  memcpy(bad, frame, sizeof frame);
  bad[6] = 0; /* a count of 0 in a frame of the length that count implies */
  CHECK(run, tfw_decode_frame(bad, TFW_FRAME_BYTES(0), &h, out, 3) == TFW_ERR_BAD_COUNT);
  CHECK(run, tfw_decode_frame(bad, len, &h, out, 3) == TFW_ERR_BAD_LENGTH);
  memcpy(bad, frame, sizeof frame);
  bad[13] ^= 0x10; /* one flipped data bit */
  out[0] = 77;
  CHECK(run, tfw_decode_frame(bad, len, &h, out, 3) == TFW_ERR_BAD_CHECKSUM);
  CHECK(run, out[0] == 77); /* a rejected frame leaves nothing behind */
  CHECK(run, tfw_decode_frame(frame, len, &h, out, 2) == TFW_ERR_BUFFER_TOO_SMALL);

  CHECK(run, tfw_sequence_is_newer(1, 0));
  CHECK(run, !tfw_sequence_is_newer(5, 5));
  CHECK(run, !tfw_sequence_is_newer(4, 5));
  CHECK(run, tfw_sequence_is_newer(0, 0xFFFFFFFFu)); /* wrap-around */
}
