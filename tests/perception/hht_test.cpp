// Hilbert-Huang transform against analytic cases: known Hilbert transforms, a pure tone, a tone
// plus a linear trend, two well-separated tones, and the completeness of the decomposition.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "tactile/perception/hht.hpp"

namespace hht = tactile::perception::hht;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRateHz = 2200.0;

std::vector<double> tone(double f_hz, std::size_t n, double amplitude = 1.0, double phase = 0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i)
    x[i] = amplitude * std::cos(2 * kPi * f_hz * static_cast<double>(i) / kRateHz + phase);
  return x;
}

double rms_interior(const std::vector<double>& a, const std::vector<double>& b, double trim) {
  const auto skip = static_cast<std::size_t>(trim * static_cast<double>(a.size()));
  double s = 0;
  std::size_t n = 0;
  for (std::size_t i = skip; i + skip < a.size(); ++i, ++n) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / static_cast<double>(n));
}

}  // namespace

TEST(Fft, MatchesDirectDftForOddAndPowerOfTwoLengths) {
  for (std::size_t n : {7u, 16u, 45u, 100u}) {
    std::vector<std::complex<double>> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = {std::sin(0.3 * i) + 0.1 * i, std::cos(1.7 * i)};
    const auto X = hht::fft(x);
    for (std::size_t k = 0; k < n; ++k) {
      std::complex<double> direct = 0;
      for (std::size_t i = 0; i < n; ++i)
        direct += x[i] * std::polar(1.0, -2 * kPi * static_cast<double>(k * i) / n);
      EXPECT_NEAR(std::abs(X[k] - direct), 0.0, 1e-9 * n) << "n=" << n << " k=" << k;
    }
    const auto back = hht::fft(X, true);
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(std::abs(back[i] / double(n) - x[i]), 0, 1e-9);
  }
}

TEST(Hilbert, CosineBecomesSineAndSineBecomesMinusCosine) {
  // Whole periods: the FFT method is exact for periodic band-limited signals.
  for (std::size_t n : {512u, 550u}) {
    const double cycles = 11;
    std::vector<double> c(n), s(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double p = 2 * kPi * cycles * static_cast<double>(i) / static_cast<double>(n);
      c[i] = std::cos(p);
      s[i] = std::sin(p);
    }
    const auto hc = hht::hilbert(c);
    const auto hs = hht::hilbert(s);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(hc[i], s[i], 1e-9);
      EXPECT_NEAR(hs[i], -c[i], 1e-9);
    }
  }
}

TEST(Hilbert, ConstantHasZeroTransform) {
  const auto h = hht::hilbert(std::vector<double>(64, 3.0));
  for (double v : h) EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(InstantaneousFrequency, PureToneIsItsFrequency) {
  for (double f : {37.0, 150.0, 400.0}) {
    const auto x = tone(f, 2200, 1.0, 0.3);
    const auto inst = hht::instantaneous_frequency_hz(x, kRateHz);
    for (std::size_t i = 220; i < 1980; ++i) ASSERT_NEAR(inst[i], f, 0.02 * f) << i;
    EXPECT_NEAR(hht::mean_if_first_imf_hz(x, kRateHz), f, 0.01 * f);
  }
}

TEST(Emd, ToneIsItsOwnFirstImf) {
  const auto x = tone(100, 1100);
  const auto d = hht::emd(x);
  ASSERT_GE(d.imfs.size(), 1u);
  EXPECT_LT(rms_interior(d.imfs[0], x, 0.05), 0.02);
}

TEST(Emd, ToneOverLinearTrendGivesTheToneFirst) {
  const auto t = tone(80, 1100);
  std::vector<double> x(t.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = t[i] + 5.0 * static_cast<double>(i) / 1100.0;
  const auto d = hht::emd(x);
  ASSERT_GE(d.imfs.size(), 1u);
  EXPECT_LT(rms_interior(d.imfs[0], t, 0.05), 0.05);
  EXPECT_NEAR(hht::mean_if_first_imf_hz(x, kRateHz), 80.0, 1.5);
}

TEST(Emd, TwoSeparatedTonesGiveTheHigherFirst) {
  const auto hi = tone(330, 2200, 1.0);
  const auto lo = tone(22, 2200, 1.0, 1.0);
  std::vector<double> x(hi.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = hi[i] + lo[i];
  const auto d = hht::emd(x);
  ASSERT_GE(d.imfs.size(), 2u);
  EXPECT_LT(rms_interior(d.imfs[0], hi, 0.05), 0.1);
  EXPECT_LT(rms_interior(d.imfs[1], lo, 0.1), 0.15);
  EXPECT_NEAR(hht::mean_if_first_imf_hz(x, kRateHz), 330.0, 6.0);
}

TEST(Emd, ImfsAndResidueAddBackToTheSignal) {
  std::vector<double> x(900);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = std::sin(0.9 * i) + 0.5 * std::sin(0.05 * i * (1 + 0.001 * i)) + 1e-3 * i;
  const auto d = hht::emd(x);
  ASSERT_FALSE(d.imfs.empty());
  for (std::size_t i = 0; i < x.size(); ++i) {
    double sum = d.residue[i];
    for (const auto& imf : d.imfs) sum += imf[i];
    EXPECT_NEAR(sum, x[i], 1e-9);
  }
  for (int s : d.sifts) EXPECT_LE(s, hht::EmdOptions{}.max_sifts);
}

TEST(Emd, MonotonicSignalHasNoImf) {
  std::vector<double> x(100);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.01 * i * i;
  const auto d = hht::emd(x);
  EXPECT_TRUE(d.imfs.empty());
  EXPECT_EQ(hht::mean_if_first_imf_hz(x, kRateHz), 0.0);
}

TEST(Emd, RejectsBadOptions) {
  hht::EmdOptions bad;
  bad.max_sifts = 0;
  EXPECT_THROW(hht::emd({1, 2, 1, 2, 1}, bad), std::invalid_argument);
  EXPECT_THROW(hht::instantaneous_frequency_hz({1, 2}, 0.0), std::invalid_argument);
}
