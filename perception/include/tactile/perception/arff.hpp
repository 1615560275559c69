#pragma once
// WEKA's ARFF files for the perception data (the golden check runs WEKA on them): numeric
// attributes, then the class: nominal {planar, conical, spherical} for the classifier, numeric
// footprint_mm for a regressor.

#include <filesystem>
#include <string>
#include <vector>

#include "tactile/perception/cascade.hpp"

namespace tactile::perception {

enum class ArffTarget { curvature, footprint };

void write_arff(const std::filesystem::path& path, const PerceptionDataset& d,
                const std::vector<std::size_t>& samples, const std::vector<std::size_t>& columns,
                ArffTarget target);

}  // namespace tactile::perception
