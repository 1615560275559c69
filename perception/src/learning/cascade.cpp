// Data set, split and SVC/SVR cascade of paper 2 (see cascade.hpp).

#include "tactile/perception/cascade.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "tactile/common/parallel_for.hpp"
#include "tactile/perception/svm_model.hpp"

namespace tactile::perception {

using perception::Procedure;

namespace {
constexpr std::array<Procedure, 4> kProcedures = {Procedure::static_contact,
                                                  Procedure::distal_proximal,
                                                  Procedure::radial_ulnar, Procedure::roll};
}  // namespace

std::vector<std::string> perception_input_names() {
  std::vector<std::string> names;
  for (Procedure p : kProcedures) {
    const auto n = procedure_input_names(p);
    names.insert(names.end(), n.begin(), n.end());
  }
  return names;
}

PerceptionDataset build_dataset(const std::vector<perception::SurfaceFeature>& features,
                                int trials_per_feature, const TrialSource& source,
                                const DatasetBuild& build) {
  if (trials_per_feature < 2)
    throw std::invalid_argument("perception: need >= 2 trials per feature");
  PerceptionDataset d;
  d.names = perception_input_names();
  const auto trials = static_cast<std::size_t>(trials_per_feature);
  d.samples.resize(features.size() * trials);
  const int total = static_cast<int>(d.samples.size());
  int done = 0;
  std::mutex progress_mutex;
  // Each worker fills its own sample, so the data set does not depend on the thread count.
  parallel_for(d.samples.size(), worker_count(build.threads), [&](std::size_t i) {
    const std::size_t f = i / trials;
    PerceptionSample& s = d.samples[i];
    s.feature = static_cast<int>(f);
    s.trial = static_cast<int>(i % trials);
    s.curvature = static_cast<int>(features[f].curvature);
    s.footprint_mm = features[f].signed_footprint_mm();
    for (Procedure p : kProcedures) {
      const auto in = procedure_inputs(source(features[f], p, s.trial), p);
      s.inputs.insert(s.inputs.end(), in.begin(), in.end());
    }
    if (build.progress) {
      const std::lock_guard lock(progress_mutex);
      build.progress(++done, total);
    }
  });
  return d;
}

std::uint64_t simulated_trial_seed(const perception::SurfaceFeature& f, Procedure p, int trial,
                                   std::uint64_t seed) {
  const auto index = static_cast<std::uint64_t>(std::lround(f.signed_footprint_mm() * 100) + 4000 +
                                                10000 * static_cast<int>(f.curvature));
  return ((seed * 131 + index) * 8 + static_cast<std::uint64_t>(p)) * 1000 +
         static_cast<std::uint64_t>(trial);
}

PerceptionDataset simulate_dataset(int trials_per_feature, std::uint64_t seed,
                                   const perception::SensorModel& model, const DatasetBuild& build,
                                   const std::vector<perception::SurfaceFeature>& features) {
  return build_dataset(
      features, trials_per_feature,
      [&](const perception::SurfaceFeature& f, Procedure p, int trial) {
        return perception::simulate_trial(f, p, simulated_trial_seed(f, p, trial, seed), model);
      },
      build);
}

PerceptionSplit split_per_block(const PerceptionDataset& d, double test_fraction) {
  int trials = 0;
  for (const auto& s : d.samples) trials = std::max(trials, s.trial + 1);
  const int held_out = std::max(1, static_cast<int>(std::ceil(test_fraction * trials - 1e-9)));
  PerceptionSplit split;
  for (std::size_t i = 0; i < d.samples.size(); ++i)
    (d.samples[i].trial >= trials - held_out ? split.test : split.train).push_back(i);
  return split;
}

std::vector<InputSet> table2_input_sets(const PerceptionDataset& d) {
  std::vector<InputSet> sets;
  InputSet all{"all", {}};
  for (std::size_t i = 0; i < d.names.size(); ++i) all.columns.push_back(i);
  sets.push_back(all);
  for (const char* prefix : {"static.", "dp.", "ru.", "roll."}) {
    InputSet s{std::string(prefix).substr(0, std::string(prefix).size() - 1), {}};
    for (std::size_t i = 0; i < d.names.size(); ++i)
      if (d.names[i].rfind(prefix, 0) == 0) s.columns.push_back(i);
    sets.push_back(s);
  }
  return sets;
}

std::vector<std::vector<double>> select_rows(const PerceptionDataset& d,
                                             const std::vector<std::size_t>& samples,
                                             const std::vector<std::size_t>& columns) {
  std::vector<std::vector<double>> rows;
  rows.reserve(samples.size());
  for (std::size_t i : samples) {
    std::vector<double> row;
    row.reserve(columns.size());
    for (std::size_t c : columns) row.push_back(d.samples[i].inputs.at(c));
    rows.push_back(std::move(row));
  }
  return rows;
}

CascadeResult evaluate_cascade(const PerceptionDataset& d, const PerceptionSplit& split,
                               const InputSet& inputs, int degree) {
  CascadeResult r;
  r.inputs = inputs.name;
  r.degree = degree;
  SvmOptions options;
  options.degree = degree;

  std::vector<int> labels;
  for (std::size_t i : split.train) labels.push_back(d.samples[i].curvature);
  const auto classifier =
      SvmModel::train_classifier(select_rows(d, split.train, inputs.columns), labels, options);

  std::vector<SvmModel> regressors;
  for (int c = 0; c < 3; ++c) {
    std::vector<std::size_t> train;
    std::vector<double> target;
    for (std::size_t i : split.train)
      if (d.samples[i].curvature == c) {
        train.push_back(i);
        target.push_back(d.samples[i].footprint_mm);
      }
    regressors.push_back(
        SvmModel::train_regressor(select_rows(d, train, inputs.columns), target, options));
  }

  std::array<double, 3> ss_res{}, ss_tot{}, sum{};
  std::array<int, 3> count{};
  double cascade_sq = 0;
  const auto rows = select_rows(d, split.test, inputs.columns);
  for (std::size_t k = 0; k < split.test.size(); ++k) {
    const auto& s = d.samples[split.test[k]];
    const int predicted = static_cast<int>(std::lround(classifier.predict(rows[k])));
    ++r.confusion[s.curvature][predicted];
    r.correct += predicted == s.curvature;
    ++r.tested;
    const double mm = regressors[s.curvature].predict(rows[k]);
    const double cascade_mm = regressors[predicted].predict(rows[k]);
    cascade_sq += (cascade_mm - s.footprint_mm) * (cascade_mm - s.footprint_mm);
    r.predictions.push_back({s.curvature, predicted, s.footprint_mm, mm});
    ss_res[s.curvature] += (mm - s.footprint_mm) * (mm - s.footprint_mm);
    sum[s.curvature] += s.footprint_mm;
    ++count[s.curvature];
  }
  for (const auto& p : r.predictions) {
    const double m = sum[p.curvature] / count[p.curvature];
    ss_tot[p.curvature] += (p.true_mm - m) * (p.true_mm - m);
  }
  for (int c = 0; c < 3; ++c) {
    r.r2[c] = ss_tot[c] > 0 ? 1 - ss_res[c] / ss_tot[c] : 0.0;
    r.rms_mm[c] = count[c] ? std::sqrt(ss_res[c] / count[c]) : 0.0;
  }
  r.cascade_rms_mm = r.tested ? std::sqrt(cascade_sq / r.tested) : 0.0;
  return r;
}

}  // namespace tactile::perception
