// libsvm with WEKA's conventions: scaling on the training set, polynomial kernels, the target
// scaling of SMOreg, and the 90/10 split per block.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tactile/perception/cascade.hpp"
#include "tactile/perception/svm_model.hpp"

namespace perception = tactile::perception;

TEST(MinMaxScaler, ScalesToUnitRangeOnTheTrainingSet) {
  const auto s = perception::MinMaxScaler::fit({{0, 5, 7}, {10, 5, 9}, {5, 5, 8}});
  const auto v = s.apply({2.5, 99, 10});
  EXPECT_DOUBLE_EQ(v[0], 0.25);
  EXPECT_DOUBLE_EQ(v[1], 0.0);  // constant on the training set: 0, as WEKA's Normalize
  EXPECT_DOUBLE_EQ(v[2], 1.5);  // outside the training range: not clipped
  EXPECT_THROW(s.apply({1, 2}), std::invalid_argument);
}

TEST(SvmModel, SeparatesThreeWellSeparatedClasses) {
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0, 0.3);
  perception::SvmRows x;
  std::vector<int> y;
  const double centres[3][2] = {{0, 0}, {10, 0}, {0, 10}};
  for (int i = 0; i < 90; ++i) {
    const int c = i % 3;
    x.push_back({centres[c][0] + noise(rng), centres[c][1] + noise(rng), 1000 + noise(rng)});
    y.push_back(c);
  }
  for (int degree : {1, 2}) {
    perception::SvmOptions o;
    o.degree = degree;
    const auto m = perception::SvmModel::train_classifier(x, y, o);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(m.predict({centres[c][0], centres[c][1], 1000}), c) << "degree " << degree;
  }
}

// Overlapping classes, so that the exponent and C change which test rows are right: the SVMs
// that share one kernel matrix predict what each trained alone predicts.
TEST(SvmModel, SharedKernelGivesTheModelsTrainedAlone) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 1.5);
  const double centres[4][3] = {{0, 0, 5}, {2, 0, 5}, {0, 2, 5}, {2, 2, 6}};
  perception::SvmRows train, test;
  std::vector<int> labels;
  for (int i = 0; i < 100; ++i) {
    const int c = i % 4;
    std::vector<double> row;
    for (const double m : centres[c]) row.push_back(100 * (m + noise(rng)));
    (i < 60 ? train : test).push_back(row);
    if (i < 60) labels.push_back(c);
  }
  std::vector<perception::SvmOptions> options;
  for (const int degree : {1, 2, 3})
    for (const double c : {0.01, 1.0, 100.0, 1000.0}) {
      perception::SvmOptions o;
      o.degree = degree;
      o.c = c;
      options.push_back(o);
    }
  const auto shared = perception::classify_with_each(train, labels, test, options);
  ASSERT_EQ(shared.size(), options.size());
  std::vector<std::vector<int>> alone;
  for (std::size_t k = 0; k < options.size(); ++k) {
    const auto m = perception::SvmModel::train_classifier(train, labels, options[k]);
    auto& classes = alone.emplace_back();
    for (const auto& row : test) classes.push_back(static_cast<int>(std::lround(m.predict(row))));
    EXPECT_EQ(shared[k], classes) << "exponent " << options[k].degree << ", C " << options[k].c;
  }
  // The options matter here, so equal predictions are not one model's answers repeated.
  EXPECT_NE(alone.front(), alone.back());
  EXPECT_NE(alone[0], alone[2]);
}

TEST(SvmModel, RegressorRecoversALinearTargetInItsUnits) {
  // y = 3 a - 2 b + 40 on a grid; a linear kernel with the scaled target maps back exactly up
  // to the epsilon tube (1e-3 of the target range, here 50).
  perception::SvmRows x;
  std::vector<double> y;
  for (int a = 0; a <= 10; ++a)
    for (int b = 0; b <= 10; ++b) {
      x.push_back({double(a), double(b)});
      y.push_back(3.0 * a - 2.0 * b + 40);
    }
  perception::SvmOptions o;
  o.c = 100;  // little regularisation, so the fit is exact up to the tube
  const auto m = perception::SvmModel::train_regressor(x, y, o);
  EXPECT_NEAR(m.predict({5, 5}), 45.0, 0.2);
  EXPECT_NEAR(m.predict({10, 0}), 70.0, 0.2);
  EXPECT_NEAR(m.predict({0, 10}), 20.0, 0.2);
}

TEST(SvmModel, RejectsBadTrainingData) {
  EXPECT_THROW(perception::SvmModel::train_classifier({}, {}), std::invalid_argument);
  EXPECT_THROW(perception::SvmModel::train_classifier({{1}, {2, 3}}, {0, 1}),
               std::invalid_argument);
  EXPECT_THROW(perception::SvmModel::train_regressor({{1}, {2}}, {1.0}), std::invalid_argument);
  perception::SvmOptions bad;
  bad.degree = 0;
  EXPECT_THROW(perception::SvmModel::train_classifier({{1}, {2}}, {0, 1}, bad),
               std::invalid_argument);
}

TEST(PerceptionSplit, NinetyTenPerBlock) {
  perception::PerceptionDataset d;
  for (int f = 0; f < 48; ++f)
    for (int t = 0; t < 20; ++t) d.samples.push_back({f, t, f / 16, 1.0, {}});
  const auto split = perception::split_per_block(d);
  EXPECT_EQ(split.train.size(), 864u);
  EXPECT_EQ(split.test.size(), 96u);
  int per_curvature_train = 0;
  for (auto i : split.train) per_curvature_train += d.samples[i].curvature == 1;
  EXPECT_EQ(per_curvature_train, 288);
}

TEST(PerceptionCascade, PerfectInputsGivePerfectTableRow) {
  // Inputs that state the answer (a one-hot curvature code and the signed footprint, plus a
  // constant column): the classifier must be exact, every regressor near exact (R^2 ~ 1), and
  // the confusion matrix diagonal with 2 held-out trials x 16 features per curvature.
  perception::PerceptionDataset d;
  d.names = {"planar", "conical", "spherical", "footprint", "constant"};
  const double footprints[] = {1.25, 2.5, 3.75, 5, 7.5, 10, 15, 20};
  int feature = 0;
  for (int c = 0; c < 3; ++c)
    for (double sign : {1.0, -1.0})
      for (double f : footprints) {
        for (int t = 0; t < 20; ++t) {
          const double jitter = 0.01 * ((t * 7) % 5 - 2);
          d.samples.push_back({feature,
                               t,
                               c,
                               sign * f,
                               {c == 0 ? 1.0 : 0.0, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0,
                                sign * f + jitter, 3.0}});
        }
        ++feature;
      }
  const auto split = perception::split_per_block(d);
  perception::InputSet all{"all", {0, 1, 2, 3, 4}};
  const auto r = perception::evaluate_cascade(d, split, all, 1);
  EXPECT_EQ(r.tested, 96);
  EXPECT_EQ(r.correct, 96);
  for (int t = 0; t < 3; ++t)
    for (int p = 0; p < 3; ++p) EXPECT_EQ(r.confusion[t][p], t == p ? 32 : 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(r.r2[c], 0.99) << c;
    EXPECT_LT(r.rms_mm[c], 0.5) << c;
  }
  EXPECT_EQ(r.predictions.size(), 96u);
}
