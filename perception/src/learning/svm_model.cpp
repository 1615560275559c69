// libsvm behind WEKA's conventions (see svm_model.hpp).

#include "tactile/perception/svm_model.hpp"

#include <libsvm/svm.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace tactile::perception {
namespace {

void silent(const char*) {}

std::vector<svm_node> to_nodes(const std::vector<double>& scaled) {
  std::vector<svm_node> nodes(scaled.size() + 1);
  for (std::size_t i = 0; i < scaled.size(); ++i) nodes[i] = {static_cast<int>(i + 1), scaled[i]};
  nodes.back() = {-1, 0.0};
  return nodes;
}

void check_rows(const SvmRows& x, std::size_t targets) {
  if (x.empty()) throw std::invalid_argument("svm: no training rows");
  if (x.size() != targets) throw std::invalid_argument("svm: rows and targets differ in number");
  for (const auto& row : x)
    if (row.size() != x.front().size())
      throw std::invalid_argument("svm: training rows differ in length");
}

}  // namespace

MinMaxScaler MinMaxScaler::fit(const SvmRows& x) {
  MinMaxScaler s;
  if (x.empty()) return s;
  s.min = s.max = x.front();
  for (const auto& row : x)
    for (std::size_t j = 0; j < row.size(); ++j) {
      s.min[j] = std::min(s.min[j], row[j]);
      s.max[j] = std::max(s.max[j], row[j]);
    }
  return s;
}

std::vector<double> MinMaxScaler::apply(const std::vector<double>& row) const {
  if (row.size() != min.size())
    throw std::invalid_argument("svm: row has " + std::to_string(row.size()) +
                                " inputs, model expects " + std::to_string(min.size()));
  std::vector<double> out(row.size());
  for (std::size_t j = 0; j < row.size(); ++j)
    out[j] = max[j] == min[j] ? 0.0 : (row[j] - min[j]) / (max[j] - min[j]);
  return out;
}

struct SvmModel::Impl {
  MinMaxScaler scaler;
  double target_min = 0, target_range = 1;   // regression only
  std::vector<std::vector<svm_node>> nodes;  // libsvm's model points into these
  std::vector<svm_node*> rows;
  std::vector<double> y;
  svm_problem problem{};
  svm_parameter param{};
  svm_model* model = nullptr;
  ~Impl() {
    if (model) svm_free_and_destroy_model(&model);
  }

  void train(const SvmRows& x, std::vector<double> targets, int type, const SvmOptions& o) {
    scaler = MinMaxScaler::fit(x);
    for (const auto& row : x) nodes.push_back(to_nodes(scaler.apply(row)));
    // (x . y)^1 is the linear kernel; libsvm computes it without pow().
    train_nodes(std::move(targets), type, o, o.degree == 1 ? LINEAR : POLY);
  }

  // Trains on `nodes` as they are: scaled rows, or rows of a precomputed kernel.
  void train_nodes(std::vector<double> targets, int type, const SvmOptions& o, int kernel) {
    if (o.c <= 0 || o.degree < 1) throw std::invalid_argument("svm: C > 0 and degree >= 1 needed");
    for (auto& n : nodes) rows.push_back(n.data());
    y = std::move(targets);
    problem.l = static_cast<int>(rows.size());
    problem.x = rows.data();
    problem.y = y.data();
    param.svm_type = type;
    param.kernel_type = kernel;
    param.degree = o.degree;
    param.gamma = 1.0;
    param.coef0 = 0.0;
    param.C = o.c;
    param.eps = o.tolerance;
    param.p = o.epsilon;
    param.cache_size = 64;
    param.shrinking = 1;
    param.probability = 0;
    param.nr_weight = 0;
    if (const char* error = svm_check_parameter(&problem, &param))
      throw std::invalid_argument(std::string("svm: ") + error);
    // libsvm's print hook is process-wide and read by every svm_train: set it once, before any
    // training, so models trained on several threads (run_table2) do not race on it.
    static std::once_flag quiet;
    std::call_once(quiet, [] { svm_set_print_string_function(&silent); });
    model = svm_train(&problem, &param);
  }
};

SvmModel::SvmModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SvmModel::SvmModel(SvmModel&&) noexcept = default;
SvmModel& SvmModel::operator=(SvmModel&&) noexcept = default;
SvmModel::~SvmModel() = default;

SvmModel SvmModel::train_classifier(const SvmRows& x, const std::vector<int>& labels,
                                    const SvmOptions& options) {
  check_rows(x, labels.size());
  auto impl = std::make_unique<Impl>();
  impl->train(x, std::vector<double>(labels.begin(), labels.end()), C_SVC, options);
  return SvmModel(std::move(impl));
}

SvmModel SvmModel::train_regressor(const SvmRows& x, const std::vector<double>& target,
                                   const SvmOptions& options) {
  check_rows(x, target.size());
  auto impl = std::make_unique<Impl>();
  const auto [lo, hi] = std::minmax_element(target.begin(), target.end());
  impl->target_min = *lo;
  impl->target_range = *hi > *lo ? *hi - *lo : 1.0;
  std::vector<double> scaled(target.size());
  for (std::size_t i = 0; i < target.size(); ++i)
    scaled[i] = (target[i] - impl->target_min) / impl->target_range;
  impl->train(x, std::move(scaled), EPSILON_SVR, options);
  return SvmModel(std::move(impl));
}

double SvmModel::predict(const std::vector<double>& row) const {
  const auto nodes = to_nodes(impl_->scaler.apply(row));
  const double v = svm_predict(impl_->model, nodes.data());
  if (impl_->param.svm_type == EPSILON_SVR) return impl_->target_min + v * impl_->target_range;
  return v;
}

std::size_t SvmModel::support_vectors() const {
  return static_cast<std::size_t>(svm_get_nr_sv(impl_->model));
}

namespace {

// libsvm's dot product of two rows (every attribute present), in its order of summation.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0;
  for (std::size_t j = 0; j < a.size(); ++j) sum += a[j] * b[j];
  return sum;
}

// libsvm's powi: (x . y)^degree by squaring, as its POLY kernel computes it (gamma 1, coef0 0).
double kernel_power(double base, int degree) {
  double tmp = base, ret = 1.0;
  for (int t = degree; t > 0; t /= 2) {
    if (t % 2 == 1) ret *= tmp;
    tmp = tmp * tmp;
  }
  return ret;
}

// A row of libsvm's precomputed kernel: node 0 holds the row's serial number (1-based; 0 for a
// test row, which libsvm does not read), node s its kernel value with training row s.
std::vector<svm_node> kernel_row(double serial, const std::vector<double>& dots, int degree) {
  std::vector<svm_node> nodes(dots.size() + 2);
  nodes[0] = {0, serial};
  for (std::size_t s = 0; s < dots.size(); ++s)
    nodes[s + 1] = {static_cast<int>(s + 1), degree == 1 ? dots[s] : kernel_power(dots[s], degree)};
  nodes.back() = {-1, 0.0};
  return nodes;
}

}  // namespace

std::vector<std::vector<int>> classify_with_each(const SvmRows& train,
                                                 const std::vector<int>& labels,
                                                 const SvmRows& test,
                                                 const std::vector<SvmOptions>& options) {
  check_rows(train, labels.size());
  const auto scaler = MinMaxScaler::fit(train);
  SvmRows x, t;
  for (const auto& row : train) x.push_back(scaler.apply(row));
  for (const auto& row : test) t.push_back(scaler.apply(row));
  SvmRows train_dots(x.size(), std::vector<double>(x.size())), test_dots;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j <= i; ++j) train_dots[i][j] = train_dots[j][i] = dot(x[i], x[j]);
  for (const auto& row : t) {
    auto& d = test_dots.emplace_back();
    for (const auto& r : x) d.push_back(dot(row, r));
  }
  std::vector<std::vector<int>> out;
  for (const auto& o : options) {
    SvmModel::Impl svc;
    for (std::size_t i = 0; i < x.size(); ++i)
      svc.nodes.push_back(kernel_row(static_cast<double>(i + 1), train_dots[i], o.degree));
    svc.train_nodes(std::vector<double>(labels.begin(), labels.end()), C_SVC, o, PRECOMPUTED);
    auto& classes = out.emplace_back();
    for (const auto& d : test_dots) {
      const auto nodes = kernel_row(0, d, o.degree);
      classes.push_back(static_cast<int>(std::lround(svm_predict(svc.model, nodes.data()))));
    }
  }
  return out;
}

}  // namespace tactile::perception
