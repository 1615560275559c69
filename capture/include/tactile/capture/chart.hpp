#pragma once
// A small scatter chart as PNG (OpenCV drawing), for benchmark results such as throughput
// against accuracy.

#include <filesystem>
#include <string>
#include <vector>

namespace tactile::capture {

struct ChartPoint {
  std::string label;  // the legend entry; points with the same label share a colour
  double x = 0;
  double y = 0;
};

struct ChartSpec {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = true;
  bool log_y = true;
  double y_target = 0;  // a dashed horizontal line (e.g. an accuracy goal); 0 = none
  double x_target = 0;  // a dashed vertical line (e.g. a speed goal); 0 = none
};

// Points with a non-finite or (on a log axis) non-positive coordinate are left out. Throws
// std::runtime_error naming the file if it cannot be written.
void write_scatter_chart_png(const std::filesystem::path& path,
                             const std::vector<ChartPoint>& points, const ChartSpec& spec);

}  // namespace tactile::capture
