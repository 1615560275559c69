#pragma once
// What every benchmark with a table of results writes when it ends: the rows as a CSV file, their
// chart beside it (PNG and SVG), and one line naming the three.

#include <fmt/format.h>

#include <filesystem>
#include <string>

#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"

namespace tactile::cli {

// `csv_row(row)` is a row's CSV line (ending with a newline); `bench` leads the printed line.
template <typename Rows, typename CsvRow>
void write_bench_files(const std::string& bench, const std::filesystem::path& csv_path,
                       const std::string& csv_header, const Rows& rows, CsvRow csv_row,
                       const std::filesystem::path& chart_png, const XYChart& chart) {
  auto csv = csv::open_with_header(csv_path, csv_header);
  for (const auto& r : rows) csv << csv_row(r);
  csv::finish(csv, csv_path);
  const ChartFiles plot = write_scatter_chart(chart_png, chart);
  fmt::print("{}: wrote {}, {} and {}\n", bench, csv_path.string(), plot.png.string(),
             plot.svg.string());
}

}  // namespace tactile::cli
