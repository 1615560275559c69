// The statistics every module reports, against values worked by hand or given by their textbook
// definitions (numpy's quantile method "lower" for quantile).

#include "tactile/common/stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace tactile {
namespace {

TEST(Stats, MedianIsTheUpperMiddleElement) {
  EXPECT_EQ(median(std::vector<double>{5, 1, 3}), 3.0);
  EXPECT_EQ(median(std::vector<double>{4, 1, 3, 2}), 3.0);  // upper of 2 and 3
  EXPECT_EQ(median(std::vector<int>{7, 100, 8}), 8.0);
  EXPECT_EQ(median(std::vector<double>{}), 0.0);
}

TEST(Stats, QuantileIsTheLowerElementAtQTimesNMinusOne) {
  const std::vector<double> v = {50, 10, 40, 20, 30};
  EXPECT_EQ(quantile(v, 0.0), 10.0);
  EXPECT_EQ(quantile(v, 1.0), 50.0);
  EXPECT_EQ(quantile(v, 0.5), 30.0);
  EXPECT_EQ(quantile(v, 0.25), 20.0);  // index 1.0 exactly
  EXPECT_EQ(quantile(v, 0.99), 40.0);  // index 3.96: the lower element, no interpolation
  // 1..200: index floor(0.99 * 199) = 197, value 198 (numpy.quantile(..., method="lower")).
  std::vector<double> ramp;
  for (int i = 200; i >= 1; --i) ramp.push_back(i);
  EXPECT_EQ(quantile(ramp, 0.99), 198.0);
  EXPECT_EQ(quantile(std::vector<double>{1, 2, 3, 4}, 0.5), 2.0);  // the lower middle
  EXPECT_EQ(quantile(std::vector<double>{}, 0.5), 0.0);
  EXPECT_THROW(quantile(v, 1.5), std::invalid_argument);
  EXPECT_THROW(quantile(v, -0.1), std::invalid_argument);
  EXPECT_THROW(quantile(v, std::nan("")), std::invalid_argument);
}

TEST(Stats, MadOfTheTextbookSample) {
  // Median 2, absolute deviations {1, 1, 0, 0, 2, 4, 7}, whose median is 1.
  EXPECT_EQ(mad(std::vector<double>{1, 1, 2, 2, 4, 6, 9}), 1.0);
  EXPECT_EQ(mad(std::vector<float>{3, 3, 3}), 0.0);
  EXPECT_EQ(mad(std::vector<double>{}), 0.0);
}

TEST(Stats, PearsonOfWorkedExamples) {
  // Deviations {-2,-1,0,1,2} and {-2,0,1,0,1}: 6 / sqrt(10 * 6).
  EXPECT_NEAR(pearson({1, 2, 3, 4, 5}, {2, 4, 5, 4, 5}), 6.0 / std::sqrt(60.0), 1e-15);
  EXPECT_NEAR(pearson({1, 2, 3}, {-2, -4, -6}), -1.0, 1e-15);
  EXPECT_EQ(pearson({1, 2, 3}, {7, 7, 7}), 0.0);  // a constant correlates with nothing
  EXPECT_EQ(pearson({1}, {2}), 0.0);
  // Population variance of {1, 2, 3, 4, 5} is 2: not above a floor of 3.
  EXPECT_EQ(pearson({1, 2, 3, 4, 5}, {2, 4, 5, 4, 5}, 3.0), 0.0);
  EXPECT_THROW(pearson({1, 2}, {1, 2, 3}), std::invalid_argument);
}

}  // namespace
}  // namespace tactile
