#include "tactile/capture/calibration_io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/value_checks.hpp"

namespace tactile::capture {

namespace {
constexpr int kCalibrationFormatVersion = 1;

// `mm_per_px` is the homography's mean scale, written beside it: two fields that must tell the
// same story. A file where they disagree by more than a factor of 2 was edited or damaged (a
// nearly singular px_to_mm passes the determinant check and shrinks every length a
// thousandfold). The homography's local scale is taken at the image centre.
void check_scale_agrees(const Calibration& c, const std::string& where) {
  const auto& h = c.px_to_mm;
  const double x = c.image_width_px / 2.0, y = c.image_height_px / 2.0;
  const double w = h[6] * x + h[7] * y + h[8];
  const double u = h[0] * x + h[1] * y + h[2], v = h[3] * x + h[4] * y + h[5];
  const double w2 = w * w;
  const double det = ((h[0] * w - u * h[6]) * (h[4] * w - v * h[7]) -
                      (h[1] * w - u * h[7]) * (h[3] * w - v * h[6])) /
                     (w2 * w2);
  const double scale = std::sqrt(std::abs(det));
  if (!(std::isfinite(scale) && scale > 0.5 * c.mm_per_px && scale < 2 * c.mm_per_px)) {
    throw FormatError(fmt::format(
        "{}: 'px_to_mm' gives {:.3g} mm per pixel at the image centre but 'mm_per_px' says {:.3g} "
        "(edited or damaged file?)",
        where, scale, c.mm_per_px));
  }
}
}  // namespace

nlohmann::json calibration_json(const Calibration& calibration) {
  return {{"px_to_mm", calibration.px_to_mm},
          {"mm_per_px", calibration.mm_per_px},
          {"image_width_px", calibration.image_width_px},
          {"image_height_px", calibration.image_height_px},
          {"method", calibration.method}};
}

void write_calibration_json(const std::filesystem::path& path, const Calibration& calibration) {
  nlohmann::json j = calibration_json(calibration);
  j["format"] = "tactile-calibration";
  j["format_version"] = kCalibrationFormatVersion;
  write_text_atomically(path, j.dump(2) + "\n");
}

Calibration read_calibration_json(const std::filesystem::path& path) {
  const std::string where = path.string();
  const nlohmann::json j = read_json_of_format(path, "calibration file", "tactile-calibration");
  // A later version may mean the fields differently: refused rather than guessed.
  const JsonOrigin at{where};
  const auto version =
      json_integer(at, json_required(at, j, "format_version", ""), "format_version");
  if (version != kCalibrationFormatVersion) {
    at.fail(fmt::format("format_version {} is not supported (this program reads {})", version,
                        kCalibrationFormatVersion));
  }
  Calibration c;
  const auto h = json_field<std::vector<double>>(j, "px_to_mm", where);
  if (h.size() != 9) {
    throw FormatError(
        fmt::format("{}: 'px_to_mm' must hold 9 numbers (3x3), found {}", where, h.size()));
  }
  std::copy(h.begin(), h.end(), c.px_to_mm.begin());
  c.mm_per_px = json_field<double>(j, "mm_per_px", where);
  // Read as 64-bit whole numbers and range-checked before narrowing: 1e12 or 640.5 is named as
  // it was written, not wrapped into some other int.
  const auto side = [&](const char* name) {
    return static_cast<int>(checks::int_in_range(
        json_integer(at, json_required(at, j, name, ""), name), 1, kMaxImageSidePx, where, name));
  };
  c.image_width_px = side("image_width_px");
  c.image_height_px = side("image_height_px");
  c.method = j.value("method", std::string("unknown"));
  check_calibration(c, where);
  check_scale_agrees(c, where);
  return c;
}

void check_calibration(const Calibration& c, const std::string& where) {
  const auto& h = c.px_to_mm;
  for (double v : h) {
    if (!std::isfinite(v)) throw FormatError(fmt::format("{}: 'px_to_mm' is not finite", where));
  }
  const double det = h[0] * (h[4] * h[8] - h[5] * h[7]) - h[1] * (h[3] * h[8] - h[5] * h[6]) +
                     h[2] * (h[3] * h[7] - h[4] * h[6]);
  if (std::abs(det) < 1e-15) {
    throw FormatError(fmt::format("{}: 'px_to_mm' is singular", where));
  }
  // A fingertip camera sees roughly 5-50 mm; anything far outside is a wrong calibration.
  if (!(c.mm_per_px > 1e-4 && c.mm_per_px < 1.0)) {
    throw FormatError(fmt::format(
        "{}: mm_per_px = {} is implausible (expected 0.0001-1 mm per pixel)", where, c.mm_per_px));
  }
  if (c.image_width_px <= 0 || c.image_height_px <= 0) {
    throw FormatError(fmt::format("{}: image size must be positive", where));
  }
  checks::int_in_range(c.image_width_px, 1, kMaxImageSidePx, where, "image_width_px");
  checks::int_in_range(c.image_height_px, 1, kMaxImageSidePx, where, "image_height_px");
}

}  // namespace tactile::capture
