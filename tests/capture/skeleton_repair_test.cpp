#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "landmarks/skeleton_repair.hpp"

namespace tactile::capture {
namespace {

// 50 px/mm: the spur bound 0.2 mm is 10 px, short valleys and gaps 0.3 mm are 15 px, bridges
// 0.6 mm are 30 px, and valleys one ridge period (0.45 mm) apart are about 22 px apart.
constexpr double kPxPerMm = 50.0;

cv::Mat blank(int w = 80, int h = 60) {
  return cv::Mat::zeros(h, w, CV_8U);
}

void draw(cv::Mat& m, cv::Point a, cv::Point b) {
  cv::line(m, a, b, cv::Scalar(1), 1, cv::LINE_8);
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return cv::countNonZero(a != b) == 0;
}

// Endings and fork pixels by crossing number, counted here independently of the code under
// test.
struct Kinds {
  int endings = 0;
  int forks = 0;
};

Kinds kinds(const cv::Mat& s) {
  static constexpr int ring[8][2] = {{1, 0},  {1, 1},   {0, 1},  {-1, 1},
                                     {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  auto on = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < s.cols && y < s.rows && s.at<std::uint8_t>(y, x) != 0;
  };
  Kinds k;
  for (int y = 0; y < s.rows; ++y) {
    for (int x = 0; x < s.cols; ++x) {
      if (!on(x, y)) continue;
      int c = 0;
      for (int i = 0; i < 8; ++i) {
        c += (!on(x + ring[i][0], y + ring[i][1]) &&
              on(x + ring[(i + 1) % 8][0], y + ring[(i + 1) % 8][1]))
                 ? 1
                 : 0;
      }
      k.endings += c == 1;
      k.forks += c >= 3;
    }
  }
  return k;
}

TEST(SkeletonRepair, ShortSpurIsRemovedAndItsForkBecomesAValleyPoint) {
  cv::Mat s = blank();
  draw(s, {5, 30}, {75, 30});
  draw(s, {40, 29}, {40, 24});  // 6 px = 0.12 mm from the fork
  ASSERT_EQ(kinds(s).forks, 1);
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.spurs, 1);
  EXPECT_EQ(c.bridges + c.short_valleys + c.gaps_joined, 0);
  cv::Mat valley = blank();
  draw(valley, {5, 30}, {75, 30});
  EXPECT_TRUE(same(s, valley));
  EXPECT_EQ(kinds(s).forks, 0);
  EXPECT_EQ(kinds(s).endings, 2);
}

TEST(SkeletonRepair, LongSpurIsARealBifurcationAndStays) {
  cv::Mat s = blank();
  draw(s, {5, 30}, {75, 30});
  draw(s, {40, 29}, {40, 10});  // 20 px = 0.4 mm
  const cv::Mat before = s.clone();
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.spurs + c.bridges + c.short_valleys + c.gaps_joined, 0);
  EXPECT_TRUE(same(s, before));
}

TEST(SkeletonRepair, ShortValleyIsDroppedLongValleyStays) {
  cv::Mat s = blank();
  draw(s, {20, 15}, {30, 15});  // 10 px = 0.2 mm, isolated
  draw(s, {20, 40}, {60, 40});  // 40 px = 0.8 mm
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.short_valleys, 1);
  EXPECT_EQ(c.spurs + c.bridges + c.gaps_joined, 0);
  cv::Mat long_only = blank();
  draw(long_only, {20, 40}, {60, 40});
  EXPECT_TRUE(same(s, long_only));
}

TEST(SkeletonRepair, BridgeAcrossARidgeIsRemoved) {
  cv::Mat s = blank();
  draw(s, {5, 20}, {75, 20});
  draw(s, {5, 42}, {75, 42});   // one period (0.44 mm) below
  draw(s, {40, 21}, {40, 41});  // across, joining the two
  ASSERT_EQ(kinds(s).forks, 2);
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.bridges, 1);
  EXPECT_EQ(c.spurs + c.short_valleys + c.gaps_joined, 0);
  cv::Mat valleys = blank();
  draw(valleys, {5, 20}, {75, 20});
  draw(valleys, {5, 42}, {75, 42});
  EXPECT_TRUE(same(s, valleys));
  EXPECT_EQ(kinds(s).forks, 0);
  EXPECT_EQ(kinds(s).endings, 4);
}

// Two forks 15 px apart joined along the valley direction: two bifurcations in a row, not a
// bridge between valleys.
TEST(SkeletonRepair, ShortSegmentAlongTheValleysStays) {
  cv::Mat s = blank();
  draw(s, {5, 30}, {75, 30});
  draw(s, {29, 29}, {14, 14});  // branch leaving up-left at x = 30
  draw(s, {46, 31}, {61, 46});  // branch leaving down-right at x = 45
  const cv::Mat before = s.clone();
  ASSERT_EQ(kinds(s).endings, 4);
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.spurs + c.bridges + c.short_valleys + c.gaps_joined, 0);
  EXPECT_TRUE(same(s, before));
}

TEST(SkeletonRepair, BrokenValleyWithFacingEndingsIsJoined) {
  cv::Mat s = blank();
  draw(s, {5, 30}, {35, 30});
  draw(s, {45, 30}, {75, 30});  // gap of 10 px = 0.2 mm, endings face each other
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.gaps_joined, 1);
  cv::Mat whole = blank();
  draw(whole, {5, 30}, {75, 30});
  EXPECT_TRUE(same(s, whole));
  EXPECT_EQ(kinds(s).endings, 2);
}

// Offset by 3 px (17 degrees off the axis, inside 30): joined into one valley with no fork
// where the join meets the two pieces.
TEST(SkeletonRepair, SlightlyOffsetBrokenValleyIsJoinedWithoutForks) {
  cv::Mat s = blank();
  draw(s, {5, 30}, {35, 30});
  draw(s, {45, 33}, {75, 33});
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.gaps_joined, 1);
  EXPECT_EQ(kinds(s).endings, 2);
  EXPECT_EQ(kinds(s).forks, 0);
  EXPECT_EQ(s.at<std::uint8_t>(30, 5), 1);
  EXPECT_EQ(s.at<std::uint8_t>(33, 75), 1);
}

TEST(SkeletonRepair, EndingsThatDoNotFaceEachOtherOrAreFarStayApart) {
  // Side by side (0.16 mm apart, both pointing +x), a V whose endings point 53 degrees off the
  // line between them, and a facing pair 0.4 mm apart.
  cv::Mat s = blank(120, 100);
  draw(s, {5, 10}, {35, 10});
  draw(s, {5, 18}, {35, 18});
  draw(s, {20, 40}, {35, 60});
  draw(s, {60, 40}, {45, 60});
  draw(s, {5, 85}, {35, 85});
  draw(s, {55, 85}, {85, 85});
  const cv::Mat before = s.clone();
  const auto c = repair_skeleton(s, kPxPerMm);
  EXPECT_EQ(c.spurs + c.bridges + c.short_valleys + c.gaps_joined, 0);
  EXPECT_TRUE(same(s, before));
}

TEST(SkeletonRepair, EmptyOnePixelAndAllOnImages) {
  cv::Mat empty;
  const auto c0 = repair_skeleton(empty, kPxPerMm);
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(c0.spurs + c0.bridges + c0.short_valleys + c0.gaps_joined, 0);

  cv::Mat zeros = blank();
  repair_skeleton(zeros, kPxPerMm);
  EXPECT_EQ(cv::countNonZero(zeros), 0);

  // A lone pixel is a valley of length zero.
  cv::Mat one = cv::Mat::ones(1, 1, CV_8U);
  const auto c1 = repair_skeleton(one, kPxPerMm);
  EXPECT_EQ(c1.short_valleys, 1);
  EXPECT_EQ(cv::countNonZero(one), 0);

  // Not a skeleton at all: must terminate and only ever remove pixels.
  cv::Mat full = cv::Mat::ones(20, 20, CV_8U);
  repair_skeleton(full, kPxPerMm);
  EXPECT_EQ(full.size(), cv::Size(20, 20));
  EXPECT_EQ(cv::countNonZero(full > 1), 0);
}

}  // namespace
}  // namespace tactile::capture
