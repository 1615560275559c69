/*
 * Writes the fuzzing seed corpus: valid frames of the fuzzed 4 x 4 device (single, and as the
 * length-prefixed streams the device check reads), so that mutation starts from inputs that
 * reach the checksum and sequence logic instead of dying at the magic number.
 */
#include <stdio.h>
#include <string.h>

#include "tactile_fw/wire.h"

static int write_file(const char* dir, const char* name, const uint8_t* data, size_t len) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE* f = fopen(path, "wb");
  if (f == NULL) return 1;
  const size_t written = fwrite(data, 1, len, f);
  return (fclose(f) != 0 || written != len) ? 1 : 0;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: make_seeds DIR\n");
    return 2;
  }
  int16_t v[16];
  uint8_t frame[TFW_FRAME_BYTES(16)];
  uint8_t stream[8 * (1 + sizeof frame)];
  size_t stream_len = 0;
  int failures = 0;
  for (uint32_t seq = 1; seq <= 8; ++seq) {
    for (int i = 0; i < 16; ++i) v[i] = (int16_t)((int)seq * 97 * (i % 2 ? 1 : -1));
    size_t len = 0;
    const uint8_t flags = seq == 8 ? TFW_FLAG_END_OF_STREAM : 0;
    if (tfw_encode_frame(seq, flags, v, 16, frame, sizeof frame, &len) != TFW_OK) return 1;
    char name[32];
    snprintf(name, sizeof name, "frame%u", (unsigned)seq);
    failures += write_file(argv[1], name, frame, len);
    stream[stream_len++] = (uint8_t)len;
    memcpy(stream + stream_len, frame, len);
    stream_len += len;
  }
  failures += write_file(argv[1], "stream8", stream, stream_len);
  return failures == 0 ? 0 : 1;
}
