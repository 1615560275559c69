// Hilbert-Huang transform: FFT, analytic signal, instantaneous frequency, EMD (see hht.hpp).

#include "tactile/perception/hht.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tactile::perception::hht {
namespace {

using Complex = std::complex<double>;

bool is_power_of_two(std::size_t n) {
  return n != 0 && (n & (n - 1)) == 0;
}

// Complex product without the NaN and infinity recovery of the C rules (__muldc3, an out-of-line
// call per butterfly that took most of an FFT's time); the values are the same for finite inputs.
Complex times(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

void fft_radix2(std::vector<Complex>& a, bool inverse) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = 2 * std::numbers::pi / static_cast<double>(len) * (inverse ? 1 : -1);
    const Complex step(std::cos(angle), std::sin(angle));
    for (std::size_t i = 0; i < n; i += len) {
      Complex w(1);
      for (std::size_t k = 0; k < len / 2; ++k) {
        const Complex u = a[i + k];
        const Complex v = times(a[i + k + len / 2], w);
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
        w = times(w, step);
      }
    }
  }
}

// Bluestein: x_k e^{-i pi k^2/n} convolved with the chirp e^{i pi k^2/n} through a radix-2 FFT.
std::vector<Complex> fft_bluestein(const std::vector<Complex>& x, bool inverse) {
  const std::size_t n = x.size();
  std::size_t m = 1;
  while (m < 2 * n - 1) m <<= 1;
  const double sign = inverse ? 1 : -1;
  std::vector<Complex> chirp(n);
  for (std::size_t k = 0; k < n; ++k) {
    // k^2 mod 2n keeps the angle small (exact for large k).
    const auto k2 = static_cast<double>((static_cast<unsigned long long>(k) * k) % (2 * n));
    const double angle = sign * std::numbers::pi * k2 / static_cast<double>(n);
    chirp[k] = Complex(std::cos(angle), std::sin(angle));
  }
  std::vector<Complex> a(m), b(m);
  for (std::size_t k = 0; k < n; ++k) a[k] = times(x[k], chirp[k]);
  b[0] = std::conj(chirp[0]);
  for (std::size_t k = 1; k < n; ++k) b[k] = b[m - k] = std::conj(chirp[k]);
  fft_radix2(a, false);
  fft_radix2(b, false);
  for (std::size_t k = 0; k < m; ++k) a[k] = times(a[k], b[k]);
  fft_radix2(a, true);
  std::vector<Complex> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = a[k] / static_cast<double>(m) * chirp[k];
  return out;
}

struct Extrema {
  std::vector<double> max_t, max_v, min_t, min_v;
};

// Local extrema; a flat run counts once, at its middle.
Extrema find_extrema(const std::vector<double>& x) {
  Extrema e;
  const std::size_t n = x.size();
  std::size_t i = 1;
  while (i + 1 < n) {
    std::size_t j = i;
    while (j + 1 < n && x[j + 1] == x[i]) ++j;  // plateau [i, j]
    if (j + 1 >= n) break;
    const double mid = 0.5 * static_cast<double>(i + j);
    if (x[i] > x[i - 1] && x[i] > x[j + 1]) {
      e.max_t.push_back(mid);
      e.max_v.push_back(x[i]);
    } else if (x[i] < x[i - 1] && x[i] < x[j + 1]) {
      e.min_t.push_back(mid);
      e.min_v.push_back(x[i]);
    }
    i = j + 1;
  }
  return e;
}

// Mirrors the two extrema nearest each end about the end sample.
void mirror_ends(std::vector<double>& t, std::vector<double>& v, double last_t) {
  const std::size_t k = std::min<std::size_t>(2, t.size());
  std::vector<double> tt, vv;
  for (std::size_t i = k; i-- > 0;) {
    tt.push_back(-t[i]);
    vv.push_back(v[i]);
  }
  tt.insert(tt.end(), t.begin(), t.end());
  vv.insert(vv.end(), v.begin(), v.end());
  for (std::size_t i = 0; i < k; ++i) {
    tt.push_back(2 * last_t - t[t.size() - 1 - i]);
    vv.push_back(v[t.size() - 1 - i]);
  }
  // Extrema lying exactly on an end mirror onto themselves: drop the duplicate knots.
  std::vector<double> ut, uv;
  for (std::size_t i = 0; i < tt.size(); ++i) {
    if (!ut.empty() && tt[i] <= ut.back()) continue;
    ut.push_back(tt[i]);
    uv.push_back(vv[i]);
  }
  t = std::move(ut);
  v = std::move(uv);
}

// Natural cubic spline through (t, v), evaluated at 0..n-1.
std::vector<double> spline(const std::vector<double>& t, const std::vector<double>& v,
                           std::size_t n) {
  const std::size_t m = t.size();
  std::vector<double> second(m, 0.0);
  if (m > 2) {
    // Tridiagonal system for the second derivatives (Thomas algorithm).
    std::vector<double> c(m, 0.0), d(m, 0.0);
    for (std::size_t i = 1; i + 1 < m; ++i) {
      const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
      const double a = h0 / 6, b = (h0 + h1) / 3, cc = h1 / 6;
      const double rhs = (v[i + 1] - v[i]) / h1 - (v[i] - v[i - 1]) / h0;
      const double denom = b - a * c[i - 1];
      c[i] = cc / denom;
      d[i] = (rhs - a * d[i - 1]) / denom;
    }
    for (std::size_t i = m - 1; i-- > 1;) second[i] = d[i] - c[i] * second[i + 1];
  }
  std::vector<double> out(n);
  std::size_t seg = 0;
  for (std::size_t s = 0; s < n; ++s) {
    const double x = static_cast<double>(s);
    while (seg + 2 < m && x > t[seg + 1]) ++seg;
    const double h = t[seg + 1] - t[seg];
    const double a = (t[seg + 1] - x) / h, b = (x - t[seg]) / h;
    out[s] = a * v[seg] + b * v[seg + 1] +
             ((a * a * a - a) * second[seg] + (b * b * b - b) * second[seg + 1]) * h * h / 6;
  }
  return out;
}

// Mean of the upper and lower envelopes; empty when x has too few extrema for envelopes.
std::vector<double> envelope_mean(const std::vector<double>& x) {
  Extrema e = find_extrema(x);
  if (e.max_t.size() + e.min_t.size() < 3 || e.max_t.empty() || e.min_t.empty()) return {};
  const double last = static_cast<double>(x.size() - 1);
  mirror_ends(e.max_t, e.max_v, last);
  mirror_ends(e.min_t, e.min_v, last);
  const auto upper = spline(e.max_t, e.max_v, x.size());
  const auto lower = spline(e.min_t, e.min_v, x.size());
  std::vector<double> mean(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) mean[i] = 0.5 * (upper[i] + lower[i]);
  return mean;
}

}  // namespace

std::vector<Complex> fft(std::vector<Complex> x, bool inverse) {
  if (x.size() <= 1) return x;
  if (is_power_of_two(x.size())) {
    fft_radix2(x, inverse);
    return x;
  }
  return fft_bluestein(x, inverse);
}

std::vector<Complex> analytic_signal(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<Complex> spectrum = fft(std::vector<Complex>(x.begin(), x.end()));
  // Keep DC (and Nyquist for even n) once, double positive frequencies, zero negative ones.
  for (std::size_t k = 1; k < n; ++k) {
    if (2 * k < n)
      spectrum[k] *= 2.0;
    else if (2 * k > n)
      spectrum[k] = 0.0;
  }
  auto a = fft(std::move(spectrum), true);
  for (auto& v : a) v /= static_cast<double>(n);
  return a;
}

std::vector<double> hilbert(const std::vector<double>& x) {
  const auto a = analytic_signal(x);
  std::vector<double> h(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) h[i] = a[i].imag();
  return h;
}

std::vector<double> instantaneous_frequency_hz(const std::vector<double>& x, double rate_hz) {
  if (rate_hz <= 0) throw std::invalid_argument("instantaneous frequency: rate must be > 0 Hz");
  const auto a = analytic_signal(x);
  const std::size_t n = a.size();
  std::vector<double> phase(n);
  for (std::size_t i = 0; i < n; ++i) {
    phase[i] = std::arg(a[i]);
    if (i > 0) {
      double d = phase[i] - phase[i - 1];
      d -= 2 * std::numbers::pi * std::round(d / (2 * std::numbers::pi));
      phase[i] = phase[i - 1] + d;
    }
  }
  std::vector<double> f(n, 0.0);
  if (n < 2) return f;
  const double scale = rate_hz / (2 * std::numbers::pi);
  f[0] = (phase[1] - phase[0]) * scale;
  f[n - 1] = (phase[n - 1] - phase[n - 2]) * scale;
  for (std::size_t i = 1; i + 1 < n; ++i) f[i] = 0.5 * (phase[i + 1] - phase[i - 1]) * scale;
  return f;
}

Emd emd(const std::vector<double>& x, const EmdOptions& options) {
  if (options.sd_threshold <= 0 || options.max_sifts < 1 || options.max_imfs < 1)
    throw std::invalid_argument("emd: sd_threshold > 0, max_sifts >= 1, max_imfs >= 1 required");
  Emd out;
  std::vector<double> residue = x;
  while (static_cast<int>(out.imfs.size()) < options.max_imfs) {
    if (envelope_mean(residue).empty()) break;  // monotonic: nothing left to sift
    std::vector<double> h = residue;
    int sifts = 0;
    while (sifts < options.max_sifts) {
      const auto mean = envelope_mean(h);
      if (mean.empty()) break;
      double num = 0, den = 0;
      for (std::size_t i = 0; i < h.size(); ++i) {
        const double next = h[i] - mean[i];
        num += (h[i] - next) * (h[i] - next);
        den += h[i] * h[i];
        h[i] = next;
      }
      ++sifts;
      if (den == 0 || num / den < options.sd_threshold) break;
    }
    for (std::size_t i = 0; i < h.size(); ++i) residue[i] -= h[i];
    out.imfs.push_back(std::move(h));
    out.sifts.push_back(sifts);
  }
  out.residue = std::move(residue);
  return out;
}

double mean_if_first_imf_hz(const std::vector<double>& x, double rate_hz, double trim_fraction) {
  if (trim_fraction < 0 || trim_fraction >= 0.5)
    throw std::invalid_argument("mean instantaneous frequency: trim fraction must be in [0, 0.5)");
  EmdOptions options;
  options.max_imfs = 1;
  const Emd d = emd(x, options);
  if (d.imfs.empty()) return 0.0;
  const auto f = instantaneous_frequency_hz(d.imfs.front(), rate_hz);
  const auto skip = static_cast<std::size_t>(trim_fraction * static_cast<double>(f.size()));
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = skip; i + skip < f.size(); ++i, ++count) sum += f[i];
  return count ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace tactile::perception::hht
