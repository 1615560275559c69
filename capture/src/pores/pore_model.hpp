#pragma once
// The logistic pore model of PoreDetector::ridge_blob: log-odds that a candidate is a pore, as a
// quadratic function of its measures, and its training on hand-marked prints.

#include <array>
#include <span>
#include <vector>

#include "pores/pore_blobs.hpp"
#include "tactile/capture/pore_training.hpp"

namespace tactile::capture {

// Coefficients: intercept, one per measure, one per product of two measures (i <= j).
constexpr std::size_t kPoreModelSize = 1 + kPoreMeasures + kPoreMeasures * (kPoreMeasures + 1) / 2;

// Throws std::invalid_argument unless `model` has kPoreModelSize coefficients.
void check_pore_model(std::span<const double> model);

double pore_log_odds(const std::array<double, kPoreMeasures>& measures,
                     std::span<const double> model);

// Trained on all 15 PolyU HRF prints by train_pore_model (pore_model_coefficients.cpp).
std::span<const double> shipped_pore_model();

// A print's candidates (the whole image), each labelled a pore when a marked pore lies
// within `label_radius_mm`.
struct LabelledCandidates {
  std::vector<PoreCandidate> candidates;
  std::vector<char> is_pore;
};

LabelledCandidates label_pore_candidates(const PoreTrainingPrint& print, double px_per_mm,
                                         const RidgeBlobParams& params,
                                         double label_radius_mm = 0.064);

// Maximum-likelihood logistic model (Newton's method, L2 penalty `l2` on every coefficient but
// the intercept) of the labels over every candidate of every set.
std::vector<double> fit_pore_model(const std::vector<const LabelledCandidates*>& sets,
                                   double l2 = 1.0);

// label_pore_candidates on each print, then fit_pore_model (train_pore_models without folds).
std::vector<double> train_pore_model(const std::vector<PoreTrainingPrint>& prints, double px_per_mm,
                                     const RidgeBlobParams& params, double label_radius_mm = 0.064,
                                     double l2 = 1.0);

}  // namespace tactile::capture
