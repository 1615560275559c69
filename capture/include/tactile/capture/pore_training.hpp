#pragma once
// Training the pore model of PoreDetector::ridge_blob on hand-marked prints: a researcher's own
// prints (read by pore_training_io.hpp) give a model that can be saved (pore_model_io.hpp) and
// used instead of the shipped one (RidgeBlobParams::model).

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "tactile/capture/features.hpp"
#include "tactile/capture/image.hpp"

namespace tactile::capture {

struct PoreTrainingPrint {
  std::string name;  // the image file's name, recorded in model files
  GrayImage image;
  std::vector<std::array<double, 2>> pores_px;  // hand-marked pores, x and y (0-based)
};

struct PoreTrainingSettings {
  double px_per_mm = 47.0;         // scale of the prints (the shipped model's: PolyU HRF)
  double label_radius_mm = 0.064;  // a candidate this close to a marked pore is a pore
  double l2 = 1.0;                 // penalty on every coefficient but the intercept
  RidgeBlobParams params;          // the detector whose candidates are labelled
};

struct TrainedPoreModels {
  std::vector<double> model;  // trained on every print
  // With held_out: held_out[i] is trained on every print but print i (leave one print out).
  std::vector<std::vector<double>> held_out;
};

// Labels each print's candidates once (calling progress(k, n) before print k of n), then fits
// the model on all prints and, with `held_out`, one model per print on the other prints.
// Throws std::invalid_argument for no prints, or held_out with fewer than two.
TrainedPoreModels train_pore_models(const std::vector<PoreTrainingPrint>& prints,
                                    const PoreTrainingSettings& settings, bool held_out,
                                    const std::function<void(int k, int n)>& progress = {});

}  // namespace tactile::capture
