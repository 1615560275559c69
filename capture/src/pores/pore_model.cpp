#include "pores/pore_model.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "camera/cv_image.hpp"

namespace tactile::capture {

namespace {

Eigen::VectorXd expand(const std::array<double, kPoreMeasures>& m) {
  Eigen::VectorXd f(static_cast<Eigen::Index>(kPoreModelSize));
  Eigen::Index k = 0;
  f[k++] = 1.0;
  for (double v : m) f[k++] = v;
  for (std::size_t i = 0; i < kPoreMeasures; ++i) {
    for (std::size_t j = i; j < kPoreMeasures; ++j) f[k++] = m[i] * m[j];
  }
  return f;
}

}  // namespace

void check_pore_model(std::span<const double> model) {
  if (model.size() != kPoreModelSize) {
    throw std::invalid_argument(
        fmt::format("pore model has {} coefficients, expected {}", model.size(), kPoreModelSize));
  }
}

double pore_log_odds(const std::array<double, kPoreMeasures>& measures,
                     std::span<const double> model) {
  check_pore_model(model);
  const Eigen::VectorXd f = expand(measures);
  return f.dot(Eigen::Map<const Eigen::VectorXd>(model.data(), f.size()));
}

LabelledCandidates label_pore_candidates(const PoreTrainingPrint& print, double px_per_mm,
                                         const RidgeBlobParams& params, double label_radius_mm) {
  cv::Mat gray;
  as_mat(print.image).convertTo(gray, CV_32F);
  // The whole image: the marked pores cover it, and more candidates only help the fit.
  const cv::Mat everywhere = cv::Mat::ones(gray.size(), CV_8U);
  LabelledCandidates out;
  out.candidates = find_pore_candidates(gray, everywhere, px_per_mm, params);
  const double radius = label_radius_mm * px_per_mm;
  for (const auto& c : out.candidates) {
    bool pore = false;
    for (const auto& t : print.pores_px) {
      pore = pore || std::hypot(t[0] - c.x_px, t[1] - c.y_px) <= radius;
    }
    out.is_pore.push_back(pore ? 1 : 0);
  }
  return out;
}

std::vector<double> train_pore_model(const std::vector<PoreTrainingPrint>& prints, double px_per_mm,
                                     const RidgeBlobParams& params, double label_radius_mm,
                                     double l2) {
  return train_pore_models(prints, {px_per_mm, label_radius_mm, l2, params}, false).model;
}

std::vector<double> fit_pore_model(const std::vector<const LabelledCandidates*>& sets, double l2) {
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> labels;
  for (const auto* set : sets) {
    for (std::size_t i = 0; i < set->candidates.size(); ++i) {
      rows.push_back(expand(set->candidates[i].measures));
      labels.push_back(set->is_pore[i] ? 1.0 : 0.0);
    }
  }
  const auto n = static_cast<Eigen::Index>(rows.size());
  const auto d = static_cast<Eigen::Index>(kPoreModelSize);
  if (n == 0) throw std::invalid_argument("pore model: no candidates to train on");
  Eigen::MatrixXd x(n, d);
  for (Eigen::Index i = 0; i < n; ++i) x.row(i) = rows[static_cast<std::size_t>(i)].transpose();
  const Eigen::Map<const Eigen::VectorXd> y(labels.data(), n);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(d);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::ArrayXd p = 1.0 / (1.0 + (-(x * w).array()).exp());
    Eigen::VectorXd gradient = x.transpose() * (p - y.array()).matrix();
    // Hessian X' diag(p (1 - p)) X, as a symmetric rank-n update of the weighted rows.
    const Eigen::MatrixXd weighted = (x.array().colwise() * (p * (1.0 - p)).sqrt()).matrix();
    Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(d, d);
    hessian.selfadjointView<Eigen::Lower>().rankUpdate(weighted.transpose());
    for (Eigen::Index i = 1; i < d; ++i) {
      hessian(i, i) += l2;
      gradient[i] += l2 * w[i];
    }
    const Eigen::VectorXd step = hessian.selfadjointView<Eigen::Lower>().ldlt().solve(gradient);
    w -= step;
    if (step.norm() < 1e-9 * (1.0 + w.norm())) break;
  }
  return {w.data(), w.data() + w.size()};
}

}  // namespace tactile::capture
