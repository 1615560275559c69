#pragma once
// Calibration files: a small JSON document, written by `tactile calibrate` and read by
// `tactile capture --calib` (schema in docs/formats.md).

#include <filesystem>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

void write_calibration_json(const std::filesystem::path& path, const Calibration& calibration);
// Throws tactile::FormatError naming the file and the problem (bad JSON, missing or mistyped
// field, homography that is singular or maps pixels to nonsense scales).
Calibration read_calibration_json(const std::filesystem::path& path);

}  // namespace tactile::capture
