// The viewer's options as the `view` command sets them.

#include <gtest/gtest.h>

#include "tactile/display/viewer.hpp"

namespace {

// `view` loops only with --loop: a flag can turn the option on, not off, so its default is off
// (it was on, and `view` said "loop on" without --loop).
TEST(ViewerOptions, LoopIsOffUnlessAskedFor) {
  EXPECT_FALSE(tactile::display::ViewerOptions{}.loop);
}

}  // namespace
