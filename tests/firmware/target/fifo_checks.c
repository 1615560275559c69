/* FIFO: order across wrap-around, a full FIFO refuses without overwriting. */
#include "check.h"
#include "tactile_fw/fifo.h"

void fifo_checks(tfw_check_run* run) {
  static tfw_fifo fifo; /* 33 KiB: static storage, not the stack of a small target */
  tfw_fifo_init(&fifo);
  CHECK(run, tfw_fifo_count(&fifo) == 0 && tfw_fifo_front(&fifo) == NULL);
  uint32_t next_in = 0;
  uint32_t next_out = 0;
  int in_order = 1;
  /* Three capacities' worth through a FIFO kept between 1/4 and 3/4 full wraps it around. */
  for (unsigned round = 0; round < 3u * TFW_FIFO_CAPACITY; ++round) {
    while (tfw_fifo_count(&fifo) < 3u * TFW_FIFO_CAPACITY / 4u) {
      tfw_frame* slot = tfw_fifo_reserve(&fifo);
      slot->sequence = next_in++;
      tfw_fifo_commit(&fifo);
    }
    while (tfw_fifo_count(&fifo) > TFW_FIFO_CAPACITY / 4u) {
      in_order &= tfw_fifo_front(&fifo)->sequence == next_out++;
      tfw_fifo_pop(&fifo);
    }
  }
  CHECK(run, in_order);
  CHECK(run, next_in > 2u * TFW_FIFO_CAPACITY);

  tfw_fifo_clear(&fifo);
  for (unsigned i = 0; i < TFW_FIFO_CAPACITY; ++i) {
    tfw_fifo_reserve(&fifo)->sequence = i;
    tfw_fifo_commit(&fifo);
  }
  CHECK(run, tfw_fifo_full(&fifo));
  CHECK(run, tfw_fifo_reserve(&fifo) == NULL);
  CHECK(run, tfw_fifo_front(&fifo)->sequence == 0);
  CHECK(run, tfw_fifo_count(&fifo) == tfw_fifo_capacity(&fifo));
}
