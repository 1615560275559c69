#pragma once
// Support vector models with libsvm, following WEKA's conventions so results can be checked
// against WEKA's SMO and SMOreg (tests/weka.cmake):
// - every attribute scaled to [0, 1] by its minimum and maximum on the training set (WEKA's
//   Normalize; an attribute constant on the training set becomes 0); test values outside the
//   training range are not clipped;
// - regression (SMOreg) also scales the target to [0, 1] and maps predictions back;
// - polynomial kernel K(x, y) = (x . y)^degree (WEKA's PolyKernel without the lower-order term:
//   libsvm gamma = 1, coef0 = 0); C = 1; tolerance 1e-3; SVR tube epsilon 1e-3;
// - multi-class by one-against-one voting (as SMO's pairwise classifiers).

#include <memory>
#include <vector>

namespace tactile::perception {

struct SvmOptions {
  double c = 1.0;
  int degree = 1;
  double tolerance = 1e-3;
  double epsilon = 1e-3;  // SVR: width of the insensitive tube (scaled target)
};

using SvmRows = std::vector<std::vector<double>>;

struct MinMaxScaler {
  std::vector<double> min, max;
  static MinMaxScaler fit(const SvmRows& x);
  std::vector<double> apply(const std::vector<double>& row) const;
};

// The classes that SvmModel::train_classifier(train, labels, options[k]).predict gives for each
// row of `test`, for every k: [k][row]. The SVMs share the training rows' kernel matrix, computed
// once (libsvm's precomputed kernel with the same kernel values, hence the same models), so
// comparing many exponents and values of C on one fold costs little more than one.
std::vector<std::vector<int>> classify_with_each(const SvmRows& train,
                                                 const std::vector<int>& labels,
                                                 const SvmRows& test,
                                                 const std::vector<SvmOptions>& options);

class SvmModel {
 public:
  // Classification: labels are small non-negative integers.
  static SvmModel train_classifier(const SvmRows& x, const std::vector<int>& labels,
                                   const SvmOptions& options = {});
  // Regression (epsilon-SVR, target scaled to [0, 1] on the training set).
  static SvmModel train_regressor(const SvmRows& x, const std::vector<double>& target,
                                  const SvmOptions& options = {});

  // Class label (classifier) or target value (regressor) for one row of raw inputs.
  double predict(const std::vector<double>& row) const;
  std::size_t support_vectors() const;

  SvmModel(SvmModel&&) noexcept;
  SvmModel& operator=(SvmModel&&) noexcept;
  ~SvmModel();

 private:
  friend std::vector<std::vector<int>> classify_with_each(const SvmRows&, const std::vector<int>&,
                                                          const SvmRows&,
                                                          const std::vector<SvmOptions>&);
  struct Impl;
  explicit SvmModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::perception
