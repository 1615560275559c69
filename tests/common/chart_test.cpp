#include "tactile/common/chart.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

class ChartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tactile_chart_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Every element closed, in order: enough to know that an SVG reader will parse the file.
bool well_formed_xml(const std::string& s) {
  std::vector<std::string> open;
  std::size_t i = 0;
  while ((i = s.find('<', i)) != std::string::npos) {
    if (s.compare(i, 4, "<!--") == 0) {
      i = s.find("-->", i);
      if (i == std::string::npos) return false;
      continue;
    }
    const std::size_t end = s.find('>', i);
    if (end == std::string::npos) return false;
    const std::string tag = s.substr(i + 1, end - i - 1);
    i = end;
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
  }
  return open.empty() && s.find("<svg") != std::string::npos;
}

// Checks both files of a chart: the PNG decodes at the expected size and is not blank, the SVG
// is well-formed and names what a reader searches for.
void expect_chart(const tactile::ChartFiles& f, int width, int height,
                  const std::vector<std::string>& words) {
  ASSERT_TRUE(fs::is_regular_file(f.png)) << f.png;
  ASSERT_TRUE(fs::is_regular_file(f.svg)) << f.svg;
  const cv::Mat img = cv::imread(f.png.string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(img.empty()) << f.png;
  EXPECT_EQ(img.cols, width);
  EXPECT_EQ(img.rows, height);
  EXPECT_GT(cv::countNonZero(img < 200), 500) << "nearly blank: " << f.png;
  const std::string svg = read(f.svg);
  EXPECT_TRUE(well_formed_xml(svg)) << f.svg;
  for (const auto& w : words) EXPECT_THAT(svg, HasSubstr(w)) << f.svg;
}

tactile::XYChart speed_accuracy() {
  tactile::XYChart c;
  c.title = "Speed against accuracy";
  c.x = {.label = "frames per second", .scale = tactile::AxisScale::log};
  c.y = {.label = "strain RMS", .scale = tactile::AxisScale::log};
  c.series = {{.label = "dense", .x = {100, 300}, .y = {0.001, 0.01}},
              {.label = "sparse", .x = {30}, .y = {0.1}}};
  c.x_targets = {{.value = 200, .label = "speed goal"}};
  c.y_targets = {{.value = 0.005, .label = "accuracy goal"}};
  return c;
}

TEST_F(ChartTest, ScatterWritesPngAndSvgWhateverTheExtensionGiven) {
  for (const char* name : {"a.png", "b.svg", "c"}) {
    const auto f = tactile::write_scatter_chart(dir_ / name, speed_accuracy());
    EXPECT_EQ(f.png, (dir_ / name).replace_extension(".png"));
    EXPECT_EQ(f.svg, (dir_ / name).replace_extension(".svg"));
    expect_chart(f, 800, 500, {"Speed against accuracy", "frames per second", "strain RMS"});
    EXPECT_EQ(f.drawn, 3u);
    EXPECT_EQ(f.left_out, 0u);
  }
}

TEST(Chart, AddPointFindsItsSeriesByLabelOrAddsItAtTheEnd) {
  tactile::XYChart c;
  c.series.push_back({.label = "given", .x = {1}, .y = {2}});
  tactile::add_point(c, "lk", 10, 0.1);
  tactile::add_point(c, "dis", 20, 0.2);
  tactile::add_point(c, "lk", 30, 0.3);
  tactile::add_point(c, "given", 4, 5);
  ASSERT_EQ(c.series.size(), 3u);
  EXPECT_EQ(c.series[0].label, "given");
  EXPECT_EQ(c.series[0].x, (std::vector<double>{1, 4}));
  EXPECT_EQ(c.series[0].y, (std::vector<double>{2, 5}));
  EXPECT_EQ(c.series[1].label, "lk");
  EXPECT_EQ(c.series[1].x, (std::vector<double>{10, 30}));
  EXPECT_EQ(c.series[1].y, (std::vector<double>{0.1, 0.3}));
  EXPECT_EQ(c.series[2].label, "dis");
  EXPECT_EQ(c.series[2].x, (std::vector<double>{20}));
  EXPECT_FALSE(c.series[1].emphasis);
}

TEST_F(ChartTest, TheSameChartIsTheSameBytes) {
  // However many charts the process drew before (cairo numbers its surfaces).
  tactile::write_scatter_chart(dir_ / "first", speed_accuracy());
  tactile::write_line_chart(dir_ / "other", speed_accuracy());
  tactile::write_scatter_chart(dir_ / "second", speed_accuracy());
  EXPECT_EQ(read(dir_ / "first.svg"), read(dir_ / "second.svg"));
  EXPECT_EQ(read(dir_ / "first.png"), read(dir_ / "second.png"));
}

TEST_F(ChartTest, LogAxisLeavesOutNonPositiveAndNonFinitePoints) {
  auto c = speed_accuracy();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.series.push_back({.label = "broken",
                      .x = {-1, 50, 0, nan, 50, INFINITY},
                      .y = {0.01, 0, 0.01, 0.01, -0.5, 0.01}});
  const auto f = tactile::write_scatter_chart(dir_ / "log", c);
  EXPECT_EQ(f.drawn, 3u);
  EXPECT_EQ(f.left_out, 6u);
  expect_chart(f, 800, 500, {"3 points drawn, 6 left out"});

  // The axes still fit the drawn points: the same image as without the broken points, apart
  // from the legend entry of the broken series.
  auto without = speed_accuracy();
  without.series.push_back({.label = "broken"});
  const auto g = tactile::write_scatter_chart(dir_ / "clean", without);
  const cv::Mat a = cv::imread(f.png.string()), b = cv::imread(g.png.string());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST_F(ChartTest, LinearAxesToo) {
  tactile::XYChart c;
  c.title = "Predicted against true";
  c.x = {.label = "true (mm)", .min = -25, .max = 25};
  c.y = {.label = "predicted (mm)", .min = -25, .max = 25};
  c.series = {{.label = "planar", .x = {-20, 0, 20}, .y = {-18, 1, 19}}};
  c.identity_line = true;
  c.width = 600;
  c.height = 620;
  expect_chart(tactile::write_scatter_chart(dir_ / "fig7.svg", c), 600, 620,
               {"Predicted against true", "true (mm)", "predicted (mm)"});
}

TEST_F(ChartTest, LineChartWithCategories) {
  tactile::XYChart c;
  c.title = "Accuracy per footprint";
  c.x = {.label = "footprint (mm)", .categories = {"-20", "-1.25", "+1.25", "+20"}};
  c.y = {.label = "accuracy (%)", .min = 0, .max = 100};
  c.series = {{.label = "all", .x = {0, 1, 2, 3}, .y = {100, 40, 50, 90}, .emphasis = true},
              {.label = "roll", .x = {0, 1, 2, 3}, .y = {90, 30, NAN, 80}}};
  c.y_targets = {{.value = 100.0 / 3, .label = "chance"}};
  const auto f = tactile::write_line_chart(dir_ / "lines.png", c);
  EXPECT_EQ(f.drawn, 7u);
  EXPECT_EQ(f.left_out, 1u);
  expect_chart(f, 800, 500, {"Accuracy per footprint", "footprint (mm)", "accuracy (%)"});
}

TEST_F(ChartTest, BarChartHeightGrowsWithTheBars) {
  tactile::BarChart c{.title = "Correlation per run",
                      .value_label = "Pearson r",
                      .labels = {"run 1", "run 2", "run 3"},
                      .values = {0.9, -0.2, NAN},
                      .colours = {0, 1, 1},
                      .legend = {"integrated", "per frame"},
                      .min = -1,
                      .max = 1,
                      .footer = "tactile 0.1.0"};
  const auto f = tactile::write_bar_chart(dir_ / "bars.png", c);
  EXPECT_EQ(f.drawn, 2u);
  EXPECT_EQ(f.left_out, 1u);
  expect_chart(f, 900, 130 + 22 * 3, {"Correlation per run", "Pearson r"});
}

TEST_F(ChartTest, HeatmapOfAConfusionMatrix) {
  tactile::HeatmapChart c{.title = "Confusion",
                          .x_label = "predicted class",
                          .y_label = "true class",
                          .row_names = {"silk", "wool"},
                          .column_names = {"silk", "wool"},
                          .values = {{9, 1}, {0, 10}}};
  const auto f = tactile::write_heatmap(dir_ / "confusion.svg", c);
  EXPECT_EQ(f.drawn, 4u);
  expect_chart(f, 200 + 2 * 36, 180 + 2 * 36, {"Confusion", "predicted class", "true class"});
}

TEST_F(ChartTest, EmptyChartsStillWriteFilesSayingNoData) {
  tactile::XYChart xy{.title = "Nothing", .x = {.label = "x"}, .y = {.label = "y"}};
  xy.x.scale = tactile::AxisScale::log;
  for (const auto& f :
       {tactile::write_scatter_chart(dir_ / "s", xy), tactile::write_line_chart(dir_ / "l", xy),
        tactile::write_bar_chart(dir_ / "b", {.title = "Nothing"}),
        tactile::write_heatmap(dir_ / "h", {.title = "Nothing"})}) {
    EXPECT_EQ(f.drawn, 0u);
    EXPECT_TRUE(fs::is_regular_file(f.png));
    EXPECT_FALSE(cv::imread(f.png.string()).empty()) << f.png;
    const std::string svg = read(f.svg);
    EXPECT_TRUE(well_formed_xml(svg)) << f.svg;
    EXPECT_THAT(svg, HasSubstr("no data"));
  }
}

TEST_F(ChartTest, UnwritablePathThrowsNamingIt) {
  const fs::path p = dir_ / "missing" / "chart.png";
  try {
    tactile::write_scatter_chart(p, speed_accuracy());
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir_ / "missing" / "chart.png").string()));
  }
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
}

TEST_F(ChartTest, MismatchedSeriesAreRefused) {
  tactile::XYChart c{.series = {{.label = "bad", .x = {1, 2}, .y = {1}}}};
  EXPECT_THROW(tactile::write_line_chart(dir_ / "bad", c), std::invalid_argument);
}

}  // namespace
