#pragma once
// Landmarks of one prism fingerprint image: sweat pores and valley minutiae (the first paper's
// feature extraction; docs/capture-models.md explains each step).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/names.hpp"

namespace tactile::capture {

// How pores are found. `paper`: bright 4-connected blobs of the binarised image (the first
// paper's rule; misses every pore that opens into a valley). `ridge_blob`: bright spots above
// the grey level of their own ridge (the image smoothed along the local ridge direction on
// both sides of the spot), each described by a few measures (brightness against the print's
// ridge noise and against its own pores, place across the ridge, size) that a small logistic
// model trained on hand-marked real prints turns into a pore probability.
enum class PoreDetector { paper, ridge_blob };
inline constexpr std::array<Named<PoreDetector>, 2> kPoreDetectorNames = {{
    {PoreDetector::paper, "paper"},
    {PoreDetector::ridge_blob, "ridge-blob"},
}};
inline std::string to_string(PoreDetector d) {
  return name_in(kPoreDetectorNames, d);
}

// Parameters of PoreDetector::ridge_blob (millimetres; chosen at about 47 px/mm on the PolyU HRF
// prints; docs/capture-models.md section 5b says how).
struct RidgeBlobParams {
  double orientation_sigma_mm = 0.106;   // structure-tensor smoothing (orientation field)
  double along_sigma_mm = 0.106;         // ridge level: smoothing along the ridge ...
  double across_sigma_mm = 0.032;        // ... and across it (keeps ridges apart)
  double pore_radius_mm = 0.04;          // ... leaving out this much on either side of the spot
  int orientations = 12;                 // quantised ridge directions
  double pore_sigma_mm = 0.015;          // smoothing of the brightness above the ridge level
  double window_mm = 0.53;               // ridge/valley envelope window (about one ridge period)
  double min_ridge_depth = 0.3;          // candidates: 0 = valley level, 1 = ridge bottom
  double noise_ridge_depth = 0.65;       // ridge noise is measured on pixels this deep ...
  double noise_block_mm = 0.85;          // ... over the print and in blocks of this size
  double suppression_radius_mm = 0.064;  // one pore per disc of this radius (strongest kept)
  double min_log_odds = -0.5;            // keep a candidate whose pore log-odds exceed this
  // Coefficients of the pore model (pore_model.hpp); empty = the shipped model, trained on all
  // 15 PolyU HRF prints.
  std::vector<double> model;
  // Workers for the per-pixel ridge-level filter (rows split between them; the result does not
  // depend on the count). One by default: callers that detect several frames at once already
  // keep every core busy.
  int threads = 1;
};

struct FeatureParams {
  PoreDetector pore_detector = PoreDetector::paper;
  RidgeBlobParams ridge_blob;
  double smoothing_sigma_mm = 0.015;  // Gaussian pre-smoothing (about one camera pixel)
  double local_window_mm = 2.0;       // local mean / variance window (paper: about 2 mm)
  // Background (no contact): low local contrast and a local mean above the image's mean,
  // measured over about one ridge period so that the print's edge does not count as contrast.
  double background_window_mm = 0.6;
  double background_max_std = 12.0;  // grey levels
  double background_min_mean_ratio = 1.0;
  // Pores: 4-connected bright blobs inside ridges.
  double pore_min_area_mm2 = 0.003;  // below this a blob is noise
  double pore_max_area_mm2 = 0.2;    // the paper's bound
  double pore_max_extent_mm = 0.3;   // ours: rejects short valley fragments the area bound passes
  double pore_min_fill = 0.45;       // blob area / bounding-box area, rejects thin fragments
  bool find_minutiae = true;
  double minutia_min_separation_mm = 0.35;  // closer minutiae are repair artefacts: drop both
  double border_margin_mm = 0.25;  // no features this close to the image edge or background
};

// px_per_mm converts the millimetre parameters to pixels.
std::vector<Feature> extract_features(const GrayImage& image, double px_per_mm,
                                      const FeatureParams& params = {});

// CSV with header type,x_px,y_px,x_mm,y_mm,orientation_rad.
void write_features_csv(const std::filesystem::path& path, const std::vector<Feature>& features,
                        const Calibration& calibration);

}  // namespace tactile::capture
