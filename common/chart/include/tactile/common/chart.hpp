#pragma once
// The project's one chart module. A chart is a plain description (title, axes, series); each
// writer draws it once and writes it twice: NAME.png to look at and NAME.svg, vector, for papers.
// The drawing library stays inside chart.cpp, so no module that draws a chart depends on it.
//
// Paths: the writers take NAME with or without an extension; any extension is replaced, so
// "out/fig.png", "out/fig.svg" and "out/fig" all write out/fig.png and out/fig.svg. The folder
// must exist. A file that cannot be written throws std::runtime_error naming its path; both files
// are written atomically (common/atomic_write.hpp), so a failed write leaves an older chart whole.
//
// Sizes: the PNG is width x height pixels and the SVG width x height points, the same drawing.
// Points with a non-finite coordinate, or a non-positive one on a log axis, are left out (and
// counted), never drawn at the edge. A chart with nothing to draw is still written, with its
// title and axes, and says "no data".
//
// The SVG's text is drawn as glyph outlines (so it looks the same without the fonts), which a
// text search cannot find; the title, axis labels, legend entries and the count of drawn and
// left-out points are therefore also in its <title> and <desc> elements.
//
// Fields default to {} so that designated initializers may name only what they need.

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace tactile {

enum class AxisScale { linear, log };

struct ChartAxis {
  std::string label{};
  AxisScale scale = AxisScale::linear;
  // Fixed limits; where NaN, the axis fits the data with a small margin.
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  // An ordinal axis: positions 0, 1, ... named by these, one tick each (for values such as
  // footprints of 1.25 to 20 mm whose small ones would otherwise share a pixel).
  std::vector<std::string> categories{};
};

struct ChartSeries {
  std::string label{};  // the legend entry; "" = not in the legend
  std::vector<double> x{};
  std::vector<double> y{};  // as many as x
  bool emphasis = false;    // drawn thicker, for the series a reader should find first
};

// A dashed guide line across the plot at x = value (vertical) or y = value (horizontal), e.g. a
// speed goal, an accuracy goal or chance level.
struct ChartTarget {
  double value = 0;
  std::string label{};
};

// Scatter (markers) or line chart (series joined in the order given; a left-out point breaks
// the line).
struct XYChart {
  std::string title{};
  ChartAxis x{};
  ChartAxis y{};
  std::vector<ChartSeries> series{};
  std::vector<ChartTarget> x_targets{};  // vertical
  std::vector<ChartTarget> y_targets{};  // horizontal
  bool identity_line = false;            // dashed y = x, for predicted against true
  std::string footer{};                  // small grey text under the chart (e.g. provenance)
  int width = 800;
  int height = 500;
};

// Appends (x, y) to the series labelled `label`, first adding that series at the end when the
// chart has none: points measured one at a time then share their series' colour.
void add_point(XYChart& chart, const std::string& label, double x, double y);

// Horizontal bars, one per label, from 0 (or the nearer limit) to the value, with the value
// printed beside it ("n/a" for a non-finite one, which is left out).
struct BarChart {
  std::string title{};
  std::string value_label{};
  std::vector<std::string> labels{};
  std::vector<double> values{};       // as many as labels
  std::vector<int> colours{};         // palette index per bar (e.g. per method); empty = all 0
  std::vector<std::string> legend{};  // names of palette colours 0, 1, ...
  double min = std::numeric_limits<double>::quiet_NaN();  // value axis; NaN = fit the data
  double max = std::numeric_limits<double>::quiet_NaN();
  std::string footer{};
  int width = 900;
  int height = 0;  // 0 = 130 + 22 per bar
};

// A matrix of numbers, each cell shaded by its share of its row's total (a confusion matrix is
// read per true class) and labelled with its value; zero cells are left blank so that the
// few non-zero ones stand out.
struct HeatmapChart {
  std::string title{};
  std::string x_label{};  // names the columns
  std::string y_label{};  // names the rows
  std::vector<std::string> row_names{};
  std::vector<std::string> column_names{};
  std::vector<std::vector<double>> values{};  // row_names.size() rows of column_names.size()
  int width = 0;                              // 0 = 200 + 36 per column
  int height = 0;                             // 0 = 180 + 36 per row
};

struct ChartFiles {
  std::filesystem::path png;
  std::filesystem::path svg;
  std::size_t drawn = 0;     // points, bars or cells drawn
  std::size_t left_out = 0;  // non-finite, or non-positive on a log axis
};

ChartFiles write_scatter_chart(const std::filesystem::path& path, const XYChart& chart);
ChartFiles write_line_chart(const std::filesystem::path& path, const XYChart& chart);
ChartFiles write_bar_chart(const std::filesystem::path& path, const BarChart& chart);
ChartFiles write_heatmap(const std::filesystem::path& path, const HeatmapChart& chart);

}  // namespace tactile
