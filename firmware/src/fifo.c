/* Ring buffer of frames; see tactile_fw/fifo.h. */
#include "tactile_fw/fifo.h"

#include <stddef.h>

void tfw_fifo_init(tfw_fifo* fifo) {
  fifo->head = 0;
  fifo->count = 0;
}

uint16_t tfw_fifo_count(const tfw_fifo* fifo) {
  return fifo->count;
}

uint16_t tfw_fifo_capacity(const tfw_fifo* fifo) {
  (void)fifo;
  return (uint16_t)TFW_FIFO_CAPACITY;
}

int tfw_fifo_full(const tfw_fifo* fifo) {
  return fifo->count >= TFW_FIFO_CAPACITY;
}

tfw_frame* tfw_fifo_reserve(tfw_fifo* fifo) {
  if (tfw_fifo_full(fifo)) return NULL;
  const uint16_t tail = (uint16_t)((fifo->head + fifo->count) % TFW_FIFO_CAPACITY);
  return &fifo->slots[tail];
}

void tfw_fifo_commit(tfw_fifo* fifo) {
  if (!tfw_fifo_full(fifo)) fifo->count++;
}

const tfw_frame* tfw_fifo_front(const tfw_fifo* fifo) {
  return fifo->count == 0 ? NULL : &fifo->slots[fifo->head];
}

void tfw_fifo_pop(tfw_fifo* fifo) {
  if (fifo->count == 0) return;
  fifo->head = (uint16_t)((fifo->head + 1u) % TFW_FIFO_CAPACITY);
  fifo->count--;
}

void tfw_fifo_clear(tfw_fifo* fifo) {
  tfw_fifo_init(fifo);
}
