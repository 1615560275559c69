#ifndef TACTILE_FW_FIFO_H
#define TACTILE_FW_FIFO_H
/*
 * Fixed-capacity FIFO of deflection frames with its storage inside the struct (no heap).
 *
 * The capacity sets the latency/robustness trade-off: the host keeps the FIFO about half full,
 * so at 1 kHz a 64-frame FIFO gives 32 ms of protection against host hiccups and 32 ms of
 * added latency, like an asynchronous USB audio buffer. Storage is
 * TFW_FIFO_CAPACITY * TFW_MAX_CONTACTORS * 2 bytes (32 KiB by default); both can be lowered
 * at compile time for a smaller microcontroller.
 */
#include <stdint.h>

#include "tactile_fw/wire.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TFW_FIFO_CAPACITY
#define TFW_FIFO_CAPACITY 64u
#endif

typedef struct {
  uint32_t sequence;
  uint8_t flags;
  uint16_t contactor_count;
  int16_t deflection[TFW_MAX_CONTACTORS];
} tfw_frame;

typedef struct {
  tfw_frame slots[TFW_FIFO_CAPACITY];
  uint16_t head;  /* index of the oldest frame */
  uint16_t count; /* frames stored */
} tfw_fifo;

void tfw_fifo_init(tfw_fifo* fifo);
uint16_t tfw_fifo_count(const tfw_fifo* fifo);
uint16_t tfw_fifo_capacity(const tfw_fifo* fifo);
int tfw_fifo_full(const tfw_fifo* fifo);

/* Returns a slot to fill in place (avoids copying a frame through the stack), or NULL when
 * full. The slot becomes part of the FIFO only with tfw_fifo_commit(). */
tfw_frame* tfw_fifo_reserve(tfw_fifo* fifo);
void tfw_fifo_commit(tfw_fifo* fifo);

/* The oldest frame, or NULL when empty; tfw_fifo_pop() then discards it. */
const tfw_frame* tfw_fifo_front(const tfw_fifo* fifo);
void tfw_fifo_pop(tfw_fifo* fifo);

void tfw_fifo_clear(tfw_fifo* fifo);

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_FIFO_H */
