#pragma once
// Plots of experiment results drawn with OpenCV (PNG). Private to the mapping module.

#include <filesystem>
#include <string>
#include <vector>

namespace tactile::experiments::plots {

// One horizontal bar per label, value axis from value_min to value_max; colour_index picks a
// colour per bar (e.g. per method) and legend names the colours. The footer (provenance) is
// printed under the chart.
void bar_chart(const std::filesystem::path& path, const std::string& title,
               const std::string& value_name, const std::vector<std::string>& labels,
               const std::vector<double>& values, const std::vector<int>& colour_index,
               const std::vector<std::string>& legend, double value_min, double value_max,
               const std::string& footer);

// One line per series against time (sample i at i * dt_s), with a legend of labels.
void line_chart(const std::filesystem::path& path, const std::string& title,
                const std::string& value_name, const std::vector<std::string>& labels,
                const std::vector<std::vector<double>>& series, double dt_s,
                const std::string& footer);

}  // namespace tactile::experiments::plots
