#pragma once
// Calibration files: a small JSON document, written by `tactile calibrate` and read by
// `tactile capture --calib` (schema in docs/formats.md).

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

// The calibration's fields as a calibration file spells them, without the file's format and
// version: a synthetic scene's scene.json carries its calibration in the same words.
nlohmann::json calibration_json(const Calibration& calibration);

void write_calibration_json(const std::filesystem::path& path, const Calibration& calibration);
// Throws tactile::FormatError naming the file and the problem (bad JSON, missing or mistyped
// field, homography that is singular or maps pixels to nonsense scales).
Calibration read_calibration_json(const std::filesystem::path& path);

// The largest image side a calibration (or a strain movie) may declare, in pixels.
inline constexpr int kMaxImageSidePx = 100000;

// Throws tactile::FormatError "<where>: ..." unless `calibration` is one a camera could have:
// a finite, non-singular homography, a plausible mm_per_px and a positive image size.
void check_calibration(const Calibration& calibration, const std::string& where);

}  // namespace tactile::capture
