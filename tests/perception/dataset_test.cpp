// Building the perception data set on several threads: the same samples in the same order as
// on one, progress reported once per sample, and a failing trial stops the build with its error.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "tactile/perception/cascade.hpp"

namespace perception = tactile::perception;

namespace {

std::vector<perception::SurfaceFeature> some_features() {
  const auto all = perception::paper_features();
  return {all[0], all[17], all[40]};  // one of each curvature, bumps and pits
}

perception::TrialSource simulated() {
  return [](const perception::SurfaceFeature& f, perception::Procedure p, int trial) {
    return perception::simulate_trial(f, p, perception::simulated_trial_seed(f, p, trial, 3));
  };
}

}  // namespace

TEST(PerceptionDataset, ThreadsDoNotChangeTheSamples) {
  const auto features = some_features();
  const auto serial = perception::build_dataset(features, 3, simulated());
  std::vector<int> calls;
  perception::DatasetBuild build;
  build.threads = 3;
  build.progress = [&](int done, int total) {
    EXPECT_EQ(total, 9);
    calls.push_back(done);
  };
  const auto parallel = perception::build_dataset(features, 3, simulated(), build);
  EXPECT_EQ(parallel.names, serial.names);
  ASSERT_EQ(parallel.samples.size(), 9u);
  ASSERT_EQ(serial.samples.size(), 9u);
  for (std::size_t i = 0; i < serial.samples.size(); ++i) {
    const auto& a = serial.samples[i];
    const auto& b = parallel.samples[i];
    EXPECT_EQ(b.feature, static_cast<int>(i / 3)) << i;  // feature-then-trial order
    EXPECT_EQ(b.trial, static_cast<int>(i % 3)) << i;
    EXPECT_EQ(b.feature, a.feature) << i;
    EXPECT_EQ(b.trial, a.trial) << i;
    EXPECT_EQ(b.curvature, static_cast<int>(features[i / 3].curvature)) << i;
    EXPECT_EQ(b.footprint_mm, features[i / 3].signed_footprint_mm()) << i;
    ASSERT_EQ(b.inputs.size(), 76u) << i;
    EXPECT_EQ(b.inputs, a.inputs) << i;  // bit for bit: each trial has its own seed
  }
  // One call per sample, counting up to the total.
  ASSERT_EQ(calls.size(), 9u);
  for (std::size_t k = 0; k < calls.size(); ++k) EXPECT_EQ(calls[k], static_cast<int>(k) + 1);
}

TEST(PerceptionDataset, AFailingTrialStopsTheBuildWithItsError) {
  const auto inner = simulated();
  perception::TrialSource failing = [&](const perception::SurfaceFeature& f,
                                        perception::Procedure p, int trial) {
    if (trial == 1 && p == perception::Procedure::roll)
      throw std::runtime_error("recording roll_trial_1.csv: truncated row 12");
    return inner(f, p, trial);
  };
  perception::DatasetBuild build;
  build.threads = 2;
  try {
    (void)perception::build_dataset(some_features(), 2, failing, build);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("roll_trial_1.csv: truncated row 12"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)perception::build_dataset(some_features(), 1, simulated(), build),
               std::invalid_argument);  // fewer than 2 trials per feature
}
