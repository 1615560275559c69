#pragma once
// Plain data for a tactile movie: frames of lateral contactor deflections on a known layout.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/common/names.hpp"
#include "tactile/common/provenance.hpp"

namespace tactile::movie {

enum class DeflectionAxis : std::uint8_t { x = 0, y = 1 };
inline constexpr std::array<Named<DeflectionAxis>, 2> kDeflectionAxisNames = {{
    {DeflectionAxis::x, "x"},
    {DeflectionAxis::y, "y"},
}};
inline std::string to_string(DeflectionAxis axis) {
  return name_in(kDeflectionAxisNames, axis);
}

// Geometry and limits of a contactor array. Contactor (row, col) rests at
// (col * pitch_x_mm, row * pitch_y_mm) relative to contactor (0, 0).
struct Layout {
  std::string name;  // "stress", "stress2", "latero" or a custom name
  std::int32_t rows = 0;
  std::int32_t cols = 0;
  double pitch_x_mm = 1.0;
  double pitch_y_mm = 1.0;
  double contactor_width_mm = 0.5;
  double contactor_height_mm = 0.5;
  DeflectionAxis axis = DeflectionAxis::x;
  double deflection_min_um = -50;
  double deflection_max_um = 50;
  double max_rate_hz = 700;

  std::int32_t contactor_count() const { return rows * cols; }
};

// How a movie was made; stored with it so every file says where it came from.
using Provenance = tactile::Provenance;

struct TactileMovie {
  Layout layout;
  double rate_hz = 700;
  std::int32_t frame_count = 0;
  // frame-major, then row-major: deflection_um[(f * rows + r) * cols + c]
  std::vector<float> deflection_um;
  Provenance provenance;

  std::span<const float> frame(std::int32_t f) const {
    const auto n = static_cast<std::size_t>(layout.contactor_count());
    return {deflection_um.data() + static_cast<std::size_t>(f) * n, n};
  }
  std::span<float> frame(std::int32_t f) {
    const auto n = static_cast<std::size_t>(layout.contactor_count());
    return {deflection_um.data() + static_cast<std::size_t>(f) * n, n};
  }
  double duration_s() const { return rate_hz > 0 ? frame_count / rate_hz : 0.0; }
};

// Built-in layouts of the STReSS family.
Layout stress_layout();   // 10 x 10, 1 mm pitch, 700 Hz
Layout stress2_layout();  // 8 x 8, 1.2 mm x 1.4 mm
Layout latero_layout();   // 8 x 8, 1.2 mm x 1.6125 mm, contactors 0.5 x 1.4 mm, 750 Hz
inline constexpr std::array<std::string_view, 3> kBuiltinLayoutNames = {"stress", "stress2",
                                                                        "latero"};
// Looks up a built-in layout by name; throws std::invalid_argument listing the known names.
Layout layout_by_name(const std::string& name);

// Throws std::invalid_argument naming the first inconsistency (sizes, rate, NaN values).
void validate_movie(const TactileMovie& movie);

}  // namespace tactile::movie
