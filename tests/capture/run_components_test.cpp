// The run-based 4-connected labelling against OpenCV's connectedComponentsWithStats (the
// reference implementation it replaces in pore extraction): same components, same order.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "landmarks/run_components.hpp"

namespace tactile::capture {
namespace {

void expect_same_as_opencv(const cv::Mat& binary) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 4, CV_32S);
  const RunLabels mine = label_runs_4(binary);
  ASSERT_EQ(static_cast<int>(mine.components.size()), n - 1);
  for (int i = 1; i < n; ++i) {
    const RunComponent& c = mine.components[static_cast<std::size_t>(i - 1)];
    EXPECT_EQ(c.area, stats.at<int>(i, cv::CC_STAT_AREA)) << i;
    EXPECT_EQ(c.x_min, stats.at<int>(i, cv::CC_STAT_LEFT)) << i;
    EXPECT_EQ(c.y_min, stats.at<int>(i, cv::CC_STAT_TOP)) << i;
    EXPECT_EQ(c.x_max - c.x_min + 1, stats.at<int>(i, cv::CC_STAT_WIDTH)) << i;
    EXPECT_EQ(c.y_max - c.y_min + 1, stats.at<int>(i, cv::CC_STAT_HEIGHT)) << i;
  }
  long covered = 0;
  for (const PixelRun& r : mine.runs) {
    for (int x = r.x_begin; x < r.x_end; ++x) {
      ASSERT_EQ(labels.at<int>(r.y, x), r.component + 1) << "pixel " << x << "," << r.y;
      ++covered;
    }
  }
  EXPECT_EQ(covered, cv::countNonZero(binary));
}

TEST(RunComponents, RandomImagesOfEveryDensityMatchOpenCv) {
  std::mt19937 rng(7);
  for (double density : {0.05, 0.3, 0.5, 0.6, 0.9}) {
    cv::Mat binary(57, 83, CV_8U);
    std::bernoulli_distribution on(density);
    for (int y = 0; y < binary.rows; ++y) {
      for (int x = 0; x < binary.cols; ++x) binary.at<std::uint8_t>(y, x) = on(rng) ? 1 : 0;
    }
    SCOPED_TRACE(density);
    expect_same_as_opencv(binary);
  }
}

TEST(RunComponents, DiagonalNeighboursAreSeparateAndUShapesJoin) {
  // Two pixels touching only at a corner are two components under 4-connectivity; the arms of a
  // U are first seen as two runs and joined by the bottom row.
  cv::Mat binary = cv::Mat::zeros(6, 7, CV_8U);
  binary.at<std::uint8_t>(0, 0) = 1;
  binary.at<std::uint8_t>(1, 1) = 1;
  for (int y = 2; y < 6; ++y) binary.at<std::uint8_t>(y, 2) = binary.at<std::uint8_t>(y, 6) = 255;
  binary.row(5).colRange(2, 7).setTo(255);
  expect_same_as_opencv(binary);
  const RunLabels mine = label_runs_4(binary);
  ASSERT_EQ(mine.components.size(), 3u);
  EXPECT_EQ(mine.components[2].area, 4 + 4 + 3);
}

TEST(RunComponents, EmptyFullAndWrongTypeImages) {
  expect_same_as_opencv(cv::Mat::zeros(5, 5, CV_8U));
  expect_same_as_opencv(cv::Mat(5, 9, CV_8U, cv::Scalar(1)));
  EXPECT_TRUE(label_runs_4(cv::Mat()).runs.empty());
  EXPECT_THROW(label_runs_4(cv::Mat::zeros(3, 3, CV_32F)), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::capture
