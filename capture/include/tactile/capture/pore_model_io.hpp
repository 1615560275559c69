#pragma once
// Pore model files: a trained model of PoreDetector::ridge_blob with what it was trained on, as a
// small JSON document written by `tactile train-pores` and read by `--pore-model` (schema in
// docs/formats.md).

#include <filesystem>
#include <string>
#include <vector>

namespace tactile::capture {

struct PoreModelFile {
  std::vector<double> coefficients;  // RidgeBlobParams::model
  double px_per_mm = 0;              // scale of the training prints: the measures are in pixels
  double label_radius_mm = 0;
  double l2 = 0;
  double min_log_odds = 0;  // RidgeBlobParams::min_log_odds the model is meant to be used with
  std::vector<std::string> trained_on;  // names of the training prints
};

// Written atomically (atomic_write.hpp). Throws std::invalid_argument for a model of
// the wrong size or with non-finite numbers, std::runtime_error when the file cannot be written.
void write_pore_model_json(const std::filesystem::path& path, const PoreModelFile& model);

// Throws tactile::FormatError naming the file and the problem: not JSON, another format tag or
// version, a missing or mistyped field, a coefficient count other than this program's model
// size, a non-numeric or non-finite number, an implausible scale, radius, penalty.
PoreModelFile read_pore_model_json(const std::filesystem::path& path);

}  // namespace tactile::capture
