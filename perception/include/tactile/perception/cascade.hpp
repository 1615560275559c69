#pragma once
// The perception evaluation of paper 2: a data set of Table 1 inputs (76 per trial, one trial
// of each exploratory procedure per sample), the 90/10 split per block, and the cascade of a
// 3-class SVC for the order of curvature and curvature-specific SVRs for the signed footprint
// (Table 2 and Figure 7).

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tactile/perception/contact_inputs.hpp"
#include "tactile/perception/sensor_model.hpp"

namespace tactile::perception {

struct PerceptionSample {
  int feature = 0;  // index in the feature list
  int trial = 0;
  int curvature = 0;           // 0 planar, 1 conical, 2 spherical
  double footprint_mm = 0;     // signed: + bump, - pit
  std::vector<double> inputs;  // as PerceptionDataset::names
};

struct PerceptionDataset {
  std::vector<std::string> names;
  std::vector<PerceptionSample> samples;
};

// The names of the 76 inputs, procedure after procedure (static, dp, ru, roll).
std::vector<std::string> perception_input_names();

// Source of one trial's recording: (feature, procedure, trial) -> recording.
using TrialSource = std::function<perception::SensorRecording(const perception::SurfaceFeature&,
                                                              perception::Procedure, int trial)>;

// How a data set is built: trials are independent, so they run on `threads` workers (0 = all
// cores; `source` must then be safe to call from several threads). `progress(done, total)`, if
// set, is called after each sample, one call at a time.
struct DatasetBuild {
  int threads = 1;
  std::function<void(int done, int total)> progress;
};

// Inputs of every feature x trial; `source` defaults to the simulated sensor with seeds derived
// from (feature, procedure, trial, seed). The samples are in feature-then-trial order whatever
// the thread count. An exception from `source` or the analysis stops the build and is rethrown.
PerceptionDataset build_dataset(const std::vector<perception::SurfaceFeature>& features,
                                int trials_per_feature, const TrialSource& source,
                                const DatasetBuild& build = {});
// Seed of one simulated trial (what simulate_dataset passes to perception::simulate_trial), so
// other models of the same trials (experiments::simulate_skin_strain) see the same variation.
std::uint64_t simulated_trial_seed(const perception::SurfaceFeature& feature,
                                   perception::Procedure procedure, int trial, std::uint64_t seed);
PerceptionDataset simulate_dataset(
    int trials_per_feature, std::uint64_t seed = 1, const perception::SensorModel& model = {},
    const DatasetBuild& build = {},
    const std::vector<perception::SurfaceFeature>& features = perception::paper_features());

// Per feature (block), the last ceil(test_fraction * trials) trials are held out.
struct PerceptionSplit {
  std::vector<std::size_t> train, test;
};
PerceptionSplit split_per_block(const PerceptionDataset& d, double test_fraction = 0.1);

struct InputSet {
  std::string name;  // "all", "static", "dp", "ru", "roll"
  std::vector<std::size_t> columns;
};
std::vector<InputSet> table2_input_sets(const PerceptionDataset& d);

struct FootprintPrediction {
  int curvature = 0, predicted_curvature = 0;
  double true_mm = 0, predicted_mm = 0;  // from the regressor of the true curvature
};

struct CascadeResult {
  std::string inputs;
  int degree = 1;
  std::array<std::array<int, 3>, 3> confusion{};  // [true][predicted]
  int correct = 0, tested = 0;
  std::array<double, 3> r2{}, rms_mm{};  // per curvature, on held-out trials of that curvature
  double cascade_rms_mm = 0;             // footprint from the regressor the SVC chose
  std::vector<FootprintPrediction> predictions;
};

CascadeResult evaluate_cascade(const PerceptionDataset& d, const PerceptionSplit& split,
                               const InputSet& inputs, int degree);

// Rows of the selected columns (helpers shared with the WEKA check and benchmarks).
std::vector<std::vector<double>> select_rows(const PerceptionDataset& d,
                                             const std::vector<std::size_t>& samples,
                                             const std::vector<std::size_t>& columns);

}  // namespace tactile::perception
