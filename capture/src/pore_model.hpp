#pragma once
// The logistic pore model of PoreDetector::ridge_blob: log-odds that a candidate is a pore, as a
// quadratic function of its measures, and its training on hand-marked prints.

#include <array>
#include <span>
#include <vector>

#include "pore_blobs.hpp"
#include "tactile/capture/image.hpp"

namespace tactile::capture {

// Coefficients: intercept, one per measure, one per product of two measures (i <= j).
constexpr std::size_t kPoreModelSize = 1 + kPoreMeasures + kPoreMeasures * (kPoreMeasures + 1) / 2;

// Throws std::invalid_argument unless `model` has kPoreModelSize coefficients.
void check_pore_model(std::span<const double> model);

double pore_log_odds(const std::array<double, kPoreMeasures>& measures,
                     std::span<const double> model);

// Trained on all 15 PolyU HRF prints by train_pore_model (pore_model_coefficients.cpp).
std::span<const double> shipped_pore_model();

struct PoreTrainingPrint {
  GrayImage image;
  std::vector<std::array<double, 2>> pores_px;  // hand-marked pores, x and y (0-based)
};

// Maximum-likelihood logistic model (Newton's method, L2 penalty `l2` on every coefficient but
// the intercept) of "a marked pore lies within `label_radius_mm`" over every candidate of
// every print.
std::vector<double> train_pore_model(const std::vector<PoreTrainingPrint>& prints, double px_per_mm,
                                     const RidgeBlobParams& params, double label_radius_mm = 0.064,
                                     double l2 = 1.0);

}  // namespace tactile::capture
