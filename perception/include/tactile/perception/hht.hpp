#pragma once
// Hilbert-Huang transform: empirical mode decomposition (EMD) into intrinsic mode functions
// (IMFs), the Hilbert transform through an FFT, and instantaneous frequency. The perception
// evaluation (paper 2) uses the mean instantaneous frequency of the first IMF of the vibration.
//
// EMD choices (documented in docs/perception-models.md):
// - envelopes: natural cubic splines through the local maxima / minima;
// - end handling: the two extrema nearest each end are mirrored about the end sample, so the
//   splines are interpolated (not extrapolated) up to the ends;
// - sifting stops when the Cauchy-type standard deviation between consecutive sifts,
//   SD = sum (h_{k-1} - h_k)^2 / sum h_{k-1}^2 (Huang et al. 1998), falls below sd_threshold,
//   or after max_sifts sifts;
// - decomposition stops when the residue has fewer than 3 extrema (monotonic or one bend),
//   or after max_imfs IMFs.

#include <complex>
#include <vector>

namespace tactile::perception::hht {

// Discrete Fourier transform of any length: radix-2 for powers of two, Bluestein's chirp-z
// otherwise. `inverse` computes the unscaled inverse (divide by the length to invert).
std::vector<std::complex<double>> fft(std::vector<std::complex<double>> x, bool inverse = false);

// Analytic signal x + i H[x] by the FFT method (negative frequencies zeroed, positive doubled);
// exact for periodic band-limited signals, with end effects otherwise.
std::vector<std::complex<double>> analytic_signal(const std::vector<double>& x);

// Hilbert transform H[x] (imaginary part of the analytic signal): H[cos] = sin.
std::vector<double> hilbert(const std::vector<double>& x);

// Instantaneous frequency (Hz) per sample: derivative of the unwrapped phase of the analytic
// signal (central differences, one-sided at the ends).
std::vector<double> instantaneous_frequency_hz(const std::vector<double>& x, double rate_hz);

struct EmdOptions {
  double sd_threshold = 0.2;
  int max_sifts = 50;
  int max_imfs = 10;
};

struct Emd {
  std::vector<std::vector<double>> imfs;  // highest frequency first
  std::vector<double> residue;            // x == sum(imfs) + residue
  std::vector<int> sifts;                 // sifts spent on each IMF
};

// Full decomposition; `max_imfs` = 1 gives only the first IMF (what the features need).
Emd emd(const std::vector<double>& x, const EmdOptions& options = {});

// Mean instantaneous frequency (Hz) of the first IMF of x. The first and last `trim_fraction`
// of the samples are left out of the mean: there the Hilbert transform of a finite,
// non-periodic record has its end effects. Returns 0 for a record with no oscillation.
double mean_if_first_imf_hz(const std::vector<double>& x, double rate_hz,
                            double trim_fraction = 0.1);

}  // namespace tactile::perception::hht
