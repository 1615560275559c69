// The skin's ringing in the simulated vibration channel: kicked by a change of the slope the
// skin meets, so a constant slope is silent, an edge rings at the resonance in proportion to its
// change of slope, a rounded edge crossed slowly rings little, and touching down is no edge.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "tactile/perception/skin_ringing.hpp"

namespace perception = tactile::perception;

namespace {

constexpr double kRateHz = 2200.0;
constexpr double kGain = 50.0;
constexpr int kEdgeSample = 200;

// The slope met goes from 0 to `change` from sample kEdgeSample on, linearly over `ramp`
// samples (1 = a sharp edge); returns 0.1 s of ringing after it.
std::vector<double> cross_edge(double change, int ramp = 1) {
  perception::SkinRinging ringing(kRateHz, kGain);
  std::vector<double> out;
  for (int i = 0; i < kEdgeSample + static_cast<int>(0.1 * kRateHz); ++i) {
    const double progress = std::clamp((i - kEdgeSample + 1) / static_cast<double>(ramp), 0.0, 1.0);
    out.push_back(ringing.step(true, change * progress));
  }
  return out;
}

double peak(const std::vector<double>& v, std::size_t from = 0) {
  double p = 0;
  for (std::size_t i = from; i < v.size(); ++i) p = std::max(p, std::abs(v[i]));
  return p;
}

}  // namespace

TEST(SkinRinging, ConstantSlopeIsSilent) {
  perception::SkinRinging ringing(kRateHz, kGain);
  for (int i = 0; i < 500; ++i) EXPECT_EQ(ringing.step(true, 0.3), 0.0) << i;
}

TEST(SkinRinging, AnEdgeRingsAtTheResonanceInProportionToItsChangeOfSlope) {
  const auto edge = cross_edge(1.0);
  EXPECT_EQ(peak(std::vector<double>(edge.begin(), edge.begin() + kEdgeSample)), 0.0);
  // A two-pole resonator of Q = 3 at 150 Hz sampled at 2200 Hz, kicked by 1, answers
  // 1, 2 r cos(w0) = 1.69, r^2 (4 cos^2(w0) - 1) = 2.00, ... (pole radius r = exp(-w0 / 6)).
  EXPECT_NEAR(edge[kEdgeSample] / kGain, 1.0, 1e-12);
  EXPECT_NEAR(peak(edge) / kGain, 2.00, 0.01);
  // Linear: twice the change of slope, twice the ring; a falling edge rings the other way.
  const auto twice = cross_edge(2.0), falling = cross_edge(-1.0);
  for (std::size_t i = 0; i < edge.size(); ++i) {
    EXPECT_NEAR(twice[i], 2 * edge[i], 1e-9);
    EXPECT_NEAR(falling[i], -edge[i], 1e-9);
  }
  // Period from the first two upward zero crossings: 150 Hz damped by Q = 3 is 148 Hz.
  std::vector<double> crossings;
  for (std::size_t i = kEdgeSample + 1; i < edge.size() && crossings.size() < 2; ++i)
    if (edge[i - 1] < 0 && edge[i] >= 0)
      crossings.push_back(static_cast<double>(i - 1) + edge[i - 1] / (edge[i - 1] - edge[i]));
  ASSERT_EQ(crossings.size(), 2u);
  const double frequency_hz = kRateHz / (crossings[1] - crossings[0]);
  EXPECT_GT(frequency_hz, 140.0);
  EXPECT_LT(frequency_hz, 156.0);
  // Decays: Q = 3 loses a factor exp(-pi / 3) per cycle; after 0.05 s (7 cycles) under 1 %.
  EXPECT_LT(peak(edge, kEdgeSample + static_cast<std::size_t>(0.05 * kRateHz)), 0.01 * peak(edge));
}

TEST(SkinRinging, ARoundedEdgeCrossedWithinAPeriodRingsLittle) {
  // The same change of slope spread over 15 samples (one period at 150 Hz): the kicks largely
  // cancel (what is left is the resonator's answer to a kick held for a period, 0.31).
  // Over 4 samples (a 0.02 mm kink at 1 cm/s) most of the ring is left.
  const double sharp = peak(cross_edge(1.0));
  EXPECT_LT(peak(cross_edge(1.0, 15)), 0.4 * sharp);
  EXPECT_GT(peak(cross_edge(1.0, 4)), 0.8 * sharp);
}

TEST(SkinRinging, TouchingDownOnASlopeIsNoEdge) {
  perception::SkinRinging ringing(kRateHz, kGain);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(ringing.step(false, 0.0), 0.0);
  // Down on a slope of 0.8: the first slope is not a change.
  for (int i = 0; i < 100; ++i) EXPECT_EQ(ringing.step(true, 0.8), 0.0);
  // Lifting off and touching down on another slope forgets the old one.
  EXPECT_EQ(ringing.step(false, 0.0), 0.0);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(ringing.step(true, -0.5), 0.0);
}

TEST(SkinRinging, RefusesAResonanceAboveNyquistOrAnOverdampedOne) {
  EXPECT_THROW(perception::SkinRinging(2200.0, kGain, 1200.0), std::invalid_argument);
  EXPECT_THROW(perception::SkinRinging(2200.0, kGain, 0.0), std::invalid_argument);
  EXPECT_THROW(perception::SkinRinging(2200.0, kGain, 150.0, 0.4), std::invalid_argument);
  EXPECT_THROW(perception::SkinRinging(std::nan(""), kGain), std::invalid_argument);
}
