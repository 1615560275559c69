#include "tactile/capture/strain_movie.hpp"

#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "tactile/common/names.hpp"

namespace tactile::capture {

namespace {

// Each feature type's name in CSV files and tables, spelled once for writing and reading.
constexpr std::array<Named<FeatureType>, 3> kFeatureTypeNames = {{
    {FeatureType::pore, "pore"},
    {FeatureType::ending, "ending"},
    {FeatureType::bifurcation, "bifurcation"},
}};

}  // namespace

const char* feature_type_name(FeatureType type) {
  for (const auto& [value, name] : kFeatureTypeNames)
    if (value == type) return name.data();  // a literal's view: null-terminated
  return "unknown";
}

FeatureType parse_feature_type(const std::string& name) {
  for (const auto& [value, known] : kFeatureTypeNames)
    if (known == name) return value;
  throw std::invalid_argument(
      fmt::format("unknown feature type '{}' (expected pore, ending or bifurcation)", name));
}

PointMm to_mm(const Calibration& calibration, double x_px, double y_px) {
  const auto& h = calibration.px_to_mm;
  const double w = h[6] * x_px + h[7] * y_px + h[8];
  return {(h[0] * x_px + h[1] * y_px + h[2]) / w, (h[3] * x_px + h[4] * y_px + h[5]) / w};
}

void check_calibration_fits(const Calibration& calibration, int width_px, int height_px,
                            const std::string& calibration_source,
                            const std::string& image_source) {
  if ((calibration.image_width_px != 0 && calibration.image_width_px != width_px) ||
      (calibration.image_height_px != 0 && calibration.image_height_px != height_px)) {
    throw std::invalid_argument(
        fmt::format("{}: the calibration is for {} x {} px images, but {} is {} x {} px",
                    calibration_source, calibration.image_width_px, calibration.image_height_px,
                    image_source, width_px, height_px));
  }
}

Calibration uniform_calibration(double px_per_mm, int width_px, int height_px) {
  if (!(px_per_mm > 0)) {
    throw std::invalid_argument(fmt::format("px_per_mm must be positive, got {}", px_per_mm));
  }
  Calibration c;
  const double s = 1.0 / px_per_mm;
  c.px_to_mm = {s, 0, 0, 0, s, 0, 0, 0, 1};
  c.mm_per_px = s;
  c.image_width_px = width_px;
  c.image_height_px = height_px;
  c.method = fmt::format("px-per-mm {}", px_per_mm);
  return c;
}

}  // namespace tactile::capture
