#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "tactile/capture/evaluate.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"

namespace tactile::capture {

namespace {

// Runs `check`; the std::invalid_argument of a bad name or an inconsistent spec becomes a
// FormatError naming the file and element `w`.
template <typename Check>
auto as_format_error(const std::string& w, Check&& check) {
  try {
    return check();
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", w, e.what()));
  }
}

void read_print_warp(const nlohmann::json& j, const std::string& where, GroundTruth& gt) {
  const auto s = json_field<nlohmann::json>(j, "warp", where);
  const std::string w = where + " warp";
  PrintWarpSpec spec;
  spec.source = json_field<std::string>(s, "source", w);
  spec.px_per_mm = json_field<double>(s, "px_per_mm", w);
  spec.width_px = json_field<int>(s, "width_px", w);
  spec.height_px = json_field<int>(s, "height_px", w);
  spec.pattern = as_format_error(
      w, [&] { return parse_warp_pattern(json_field<std::string>(s, "pattern", w)); });
  spec.strain = json_field<double>(s, "strain", w);
  spec.width_mm = json_field<double>(s, "width_mm", w);
  spec.slide_x_mm = json_field<double>(s, "slide_x_mm", w);
  spec.slide_y_mm = json_field<double>(s, "slide_y_mm", w);
  spec.rotation_deg = json_field<double>(s, "rotation_deg", w);
  spec.frame_count = json_field<int>(s, "frame_count", w);
  spec.frame_rate_hz = json_field<double>(s, "frame_rate_hz", w);
  spec.blur_sigma_px = json_field<double>(s, "blur_sigma_px", w);
  spec.noise_sigma = json_field<double>(s, "noise_sigma", w);
  spec.brightness_drift = json_field<double>(s, "brightness_drift", w);
  spec.seed = json_field<std::uint64_t>(s, "seed", w);
  // Absent from files written before scenes had motion in physical units: the old behaviour.
  auto optional_field = [&](const char* name, auto& value) {
    if (s.contains(name)) value = json_field<std::decay_t<decltype(value)>>(s, name, w);
  };
  optional_field("travel_speed_mm_per_s", spec.travel_speed_mm_per_s);
  optional_field("exposure_s", spec.exposure_s);
  optional_field("supersample", spec.supersample);
  optional_field("contact_loss", spec.contact_loss);
  optional_field("patch_speed_mm_per_s", spec.patch_speed_mm_per_s);
  optional_field("patch_breathing", spec.patch_breathing);
  as_format_error(w, [&] { validate_print_warp(spec); });
  gt.calibration = uniform_calibration(spec.px_per_mm, spec.width_px, spec.height_px);
  gt.warp = spec;
}

void read_scene_json(const std::filesystem::path& path, GroundTruth& gt) {
  const std::string where = path.string();
  const nlohmann::json j = read_json_object(path, "scene (not a `tactile synth` folder?)");
  const std::string format =
      j.contains("format") && j["format"].is_string() ? j["format"].get<std::string>() : "";
  if (format == "tactile-print-warp") return read_print_warp(j, where, gt);
  if (format != "tactile-synthetic-scene") {
    throw FormatError(fmt::format(
        "{}: 'format' is neither tactile-synthetic-scene nor tactile-print-warp", where));
  }
  const auto s = json_field<nlohmann::json>(j, "spec", where);
  const std::string w = where + " spec";
  SceneSpec& spec = gt.spec;
  spec.scene =
      as_format_error(w, [&] { return parse_scene(json_field<std::string>(s, "scene", w)); });
  spec.speed_mm_per_s = json_field<double>(s, "speed_mm_per_s", w);
  spec.feature_height_mm = json_field<double>(s, "feature_height_mm", w);
  spec.feature_width_mm = json_field<double>(s, "feature_width_mm", w);
  spec.frame_count = json_field<int>(s, "frame_count", w);
  spec.frame_rate_hz = json_field<double>(s, "frame_rate_hz", w);
  spec.width_px = json_field<int>(s, "width_px", w);
  spec.height_px = json_field<int>(s, "height_px", w);
  spec.field_width_mm = json_field<double>(s, "field_width_mm", w);
  spec.field_height_mm = json_field<double>(s, "field_height_mm", w);
  spec.contact_semi_x_mm = json_field<double>(s, "contact_semi_x_mm", w);
  spec.contact_semi_y_mm = json_field<double>(s, "contact_semi_y_mm", w);
  spec.displacement_per_height = json_field<double>(s, "displacement_per_height", w);
  spec.ridge_period_mm = json_field<double>(s, "ridge_period_mm", w);
  spec.pore_spacing_mm = json_field<double>(s, "pore_spacing_mm", w);
  spec.pore_min_diameter_mm = json_field<double>(s, "pore_min_diameter_mm", w);
  spec.pore_max_diameter_mm = json_field<double>(s, "pore_max_diameter_mm", w);
  spec.minutiae_per_mm2 = json_field<double>(s, "minutiae_per_mm2", w);
  spec.blur_sigma_px = json_field<double>(s, "blur_sigma_px", w);
  spec.noise_sigma = json_field<double>(s, "noise_sigma", w);
  spec.seed = json_field<std::uint64_t>(s, "seed", w);
  // Fields added after format version 1 was first written keep their defaults when absent.
  const SceneSpec defaults;
  auto optional = [&](const char* name, double fallback) {
    return s.contains(name) ? json_field<double>(s, name, w) : fallback;
  };
  spec.contrast = optional("contrast", defaults.contrast);
  spec.rotation_deg = optional("rotation_deg", defaults.rotation_deg);
  spec.lateral_amplitude_mm = optional("lateral_amplitude_mm", defaults.lateral_amplitude_mm);
  spec.stick_ratio = optional("stick_ratio", defaults.stick_ratio);
  as_format_error(w, [&] { validate_scene(spec); });
  // The true calibration follows from the spec; the stored one is for other tools.
  gt.calibration = true_calibration(spec);
}

void read_landmarks_csv(const std::filesystem::path& path, GroundTruth& gt) {
  const std::string where = path.string();
  std::ifstream in(path);
  if (!in) throw FormatError(fmt::format("{}: cannot open", where));
  csv::LineReader lines(in);
  std::string line;
  constexpr std::string_view kHeader = "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm";
  if (!lines.next(line)) {
    throw FormatError(fmt::format("{}: empty file, expected header {}", where, kHeader));
  }
  if (line != kHeader) {
    throw FormatError(fmt::format("{}: line 1: header is '{}', expected header {}", where,
                                  line.substr(0, 200), kHeader));
  }
  while (lines.next(line)) {
    const std::size_t row = lines.number();
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    TruthLandmark lm;
    std::string type;
    if (!(fields >> lm.id >> type >> lm.frame >> lm.x_px >> lm.y_px >> lm.x_mm >> lm.y_mm >>
          lm.diameter_mm)) {
      throw FormatError(fmt::format("{}: line {} is not 8 numbers/words", where, row));
    }
    try {
      lm.type = parse_feature_type(type);
    } catch (const std::invalid_argument&) {
      throw FormatError(fmt::format("{}: line {}: unknown type '{}'", where, row, type));
    }
    const int frames = truth_frame_count(gt);
    if (lm.frame < 0 || lm.frame >= frames) {
      throw FormatError(
          fmt::format("{}: line {}: frame {} outside 0..{}", where, row, lm.frame, frames - 1));
    }
    gt.landmarks.push_back(lm);
  }
}

}  // namespace

GroundTruth read_ground_truth(const std::filesystem::path& dir) {
  GroundTruth gt;
  read_scene_json(dir / "scene.json", gt);
  read_landmarks_csv(dir / "landmarks.csv", gt);
  return gt;
}

}  // namespace tactile::capture
