// SIGINT and SIGTERM become a stop request on a descriptor instead of ending the process.
#include "tactile/common/stop_signals.hpp"

#include <gtest/gtest.h>
#include <signal.h>

namespace tactile {
namespace {

TEST(StopSignals, ASignalIsQueuedOnTheDescriptorAndTakenOnce) {
  StopSignals stop;
  EXPECT_FALSE(stop_requested(stop.fd()));
  EXPECT_EQ(stop.received(), 0);
  // Delivered to this (blocking) thread: without the block the default action would end the
  // test process here.
  ASSERT_EQ(::raise(SIGTERM), 0);
  EXPECT_TRUE(stop_requested(stop.fd()));
  EXPECT_TRUE(stop_requested(stop.fd()));  // polling does not take it
  EXPECT_EQ(stop.received(), SIGTERM);
  EXPECT_FALSE(stop_requested(stop.fd()));
  EXPECT_EQ(stop.received(), SIGTERM);  // kept: it is what the command exits by
  EXPECT_EQ(exit_code_for_signal(SIGINT), 130);
  EXPECT_EQ(exit_code_for_signal(SIGTERM), 143);
}

TEST(StopSignals, TheBlockIsLiftedAfterwards) {
  sigset_t before, after;
  pthread_sigmask(SIG_SETMASK, nullptr, &before);
  ASSERT_EQ(sigismember(&before, SIGINT), 0);
  {
    StopSignals stop;
    sigset_t during;
    pthread_sigmask(SIG_SETMASK, nullptr, &during);
    EXPECT_EQ(sigismember(&during, SIGINT), 1);
    EXPECT_EQ(sigismember(&during, SIGTERM), 1);
  }
  pthread_sigmask(SIG_SETMASK, nullptr, &after);
  EXPECT_EQ(sigismember(&after, SIGINT), 0);
  EXPECT_EQ(sigismember(&after, SIGTERM), 0);
  EXPECT_FALSE(stop_requested(-1));
}

// SIGINT ignored (a background job's) stays ignored: not blocked, not watched, so raising it
// asks for no stop; SIGTERM is still watched.
TEST(StopSignals, AnIgnoredSignalStaysIgnored) {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  struct sigaction before {};
  ASSERT_EQ(sigaction(SIGINT, &ignore, &before), 0);
  {
    StopSignals stop;
    sigset_t mask;
    pthread_sigmask(SIG_SETMASK, nullptr, &mask);
    EXPECT_EQ(sigismember(&mask, SIGINT), 0);
    EXPECT_EQ(sigismember(&mask, SIGTERM), 1);
    ASSERT_EQ(::raise(SIGINT), 0);
    EXPECT_FALSE(stop_requested(stop.fd()));
    EXPECT_EQ(stop.received(), 0);
    ASSERT_EQ(::raise(SIGTERM), 0);
    EXPECT_EQ(stop.received(), SIGTERM);
  }
  sigaction(SIGINT, &before, nullptr);
}

}  // namespace
}  // namespace tactile
