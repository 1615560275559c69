// The frame FIFO: order, capacity and full behaviour.
#include <gtest/gtest.h>

#include <memory>

#include "tactile_fw/fifo.h"

namespace {

TEST(Fifo, KeepsOrderAcrossWrapAround) {
  auto fifo = std::make_unique<tfw_fifo>();
  tfw_fifo_init(fifo.get());
  std::uint32_t next_in = 0, next_out = 0;
  for (int round = 0; round < 5; ++round) {
    while (tfw_frame* slot = tfw_fifo_reserve(fifo.get())) {
      slot->sequence = next_in++;
      tfw_fifo_commit(fifo.get());
      if (next_in % 7 == 0) break;
    }
    for (int k = 0; k < 5 && tfw_fifo_front(fifo.get()); ++k) {
      EXPECT_EQ(tfw_fifo_front(fifo.get())->sequence, next_out++);
      tfw_fifo_pop(fifo.get());
    }
  }
  while (const tfw_frame* f = tfw_fifo_front(fifo.get())) {
    EXPECT_EQ(f->sequence, next_out++);
    tfw_fifo_pop(fifo.get());
  }
  EXPECT_EQ(next_in, next_out);
}

TEST(Fifo, FullRefusesWithoutOverwriting) {
  auto fifo = std::make_unique<tfw_fifo>();
  tfw_fifo_init(fifo.get());
  for (std::uint32_t i = 0; i < TFW_FIFO_CAPACITY; ++i) {
    tfw_frame* slot = tfw_fifo_reserve(fifo.get());
    ASSERT_NE(slot, nullptr);
    slot->sequence = i;
    tfw_fifo_commit(fifo.get());
  }
  EXPECT_TRUE(tfw_fifo_full(fifo.get()));
  EXPECT_EQ(tfw_fifo_count(fifo.get()), TFW_FIFO_CAPACITY);
  EXPECT_EQ(tfw_fifo_reserve(fifo.get()), nullptr);
  tfw_fifo_commit(fifo.get());  // a stray commit must not grow a full FIFO
  EXPECT_EQ(tfw_fifo_count(fifo.get()), TFW_FIFO_CAPACITY);
  EXPECT_EQ(tfw_fifo_front(fifo.get())->sequence, 0u);  // oldest frame intact
  tfw_fifo_pop(fifo.get());
  EXPECT_NE(tfw_fifo_reserve(fifo.get()), nullptr);
  tfw_fifo_clear(fifo.get());
  EXPECT_EQ(tfw_fifo_front(fifo.get()), nullptr);
  tfw_fifo_pop(fifo.get());  // popping empty is harmless
  EXPECT_EQ(tfw_fifo_count(fifo.get()), 0u);
}

}  // namespace
