#pragma once
// Synthetic prism (FTIR) fingerprint sequences with exact ground truth: a fingertip slides over
// flat glass or over a Gaussian bump or hole, or is pressed on flat glass and twisted or pushed
// sideways with a sticking central patch, filmed by a camera fixed to the glass.
// The model and its assumptions are written in docs/capture-models.md.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/names.hpp"

namespace tactile::capture {

// What the fingertip does: slide over a Gaussian bump, a hole or flat glass, or press on flat glass
// and twist or push sideways with a sticking centre. The names are those of `--scene` and of
// scene and experiment files.
enum class Scene { bump, hole, flat_slide, flat_rotate, flat_stick_slip };
inline constexpr std::array<Named<Scene>, 5> kSceneNames = {{
    {Scene::bump, "bump"},
    {Scene::hole, "hole"},
    {Scene::flat_slide, "flat-slide"},
    {Scene::flat_rotate, "flat-rotate"},
    {Scene::flat_stick_slip, "flat-stick-slip"},
}};
inline constexpr auto kScenes = values_of(kSceneNames);
std::string to_string(Scene scene);
// Throws std::invalid_argument naming the bad name and the accepted ones.
Scene parse_scene(std::string_view name);

struct SceneSpec {
  Scene scene = Scene::bump;
  double speed_mm_per_s = 2.4;     // finger speed along +x over the glass
  double feature_height_mm = 0.5;  // bump height or hole depth
  double feature_width_mm = 3.0;   // full width at half maximum of the Gaussian profile
  int frame_count = 180;
  double frame_rate_hz = kCameraRateHz;
  int width_px = 640;
  int height_px = 484;
  double field_width_mm = 10.3;
  double field_height_mm = 10.9;
  // Fingertip contact patch (ellipse semi-axes); it moves with the finger.
  double contact_semi_x_mm = 4.8;
  double contact_semi_y_mm = 5.6;
  // Peak lateral skin displacement per mm of feature height (dimensionless skin compliance).
  double displacement_per_height = 0.4;
  // Partial-slip scenes (flat-rotate, flat-stick-slip): the finger does not slide; the centre of
  // the patch (elliptical radius below stick_ratio) sticks to the glass and the rim slips.
  double rotation_deg = 5.0;          // flat-rotate: the finger's twist at the last frame
  double lateral_amplitude_mm = 0.3;  // flat-stick-slip: peak rim displacement (+x, then -x)
  double stick_ratio = 0.4;           // stick radius / contact radius
  double ridge_period_mm = 0.45;
  double pore_spacing_mm = 0.55;  // mean distance between pores along a ridge
  double pore_min_diameter_mm = 0.088;
  double pore_max_diameter_mm = 0.220;
  double minutiae_per_mm2 = 0.15;
  double blur_sigma_px = 0.9;
  double noise_sigma = 2.0;  // grey levels
  // Print contrast: reflectances are pulled towards the no-contact brightness (0.9) by this
  // factor (1 = the FTIR model's ridges 0.22 / valleys 0.85; smaller = fainter print).
  double contrast = 1.0;
  std::uint64_t seed = 1;
};

// A landmark as rendered in one frame.
struct TruthLandmark {
  std::int32_t id = 0;  // the same material landmark keeps its id in every frame
  FeatureType type = FeatureType::pore;
  std::int32_t frame = 0;
  double x_px = 0;
  double y_px = 0;
  double x_mm = 0;
  double y_mm = 0;
  double diameter_mm = 0;  // pores only
};

struct SyntheticSequence {
  SceneSpec spec;
  Calibration calibration;  // the true px -> mm mapping of the synthetic camera
  std::vector<GrayImage> frames;
  GrayImage dot_grid;                    // 0.5 mm dot grid seen through the same camera
  std::vector<TruthLandmark> landmarks;  // every landmark in contact and in view, every frame
};

// Throws std::invalid_argument naming the first bad field.
void validate_scene(const SceneSpec& spec);

// Exact skin kinematics of the scene. Image-plane millimetres (origin at the top-left pixel
// centre) and skin (material) millimetres, which coincide with the image plane at frame 0 away
// from the feature.
PointMm skin_to_image(const SceneSpec& spec, PointMm skin, int frame);
PointMm image_to_skin(const SceneSpec& spec, PointMm image, int frame);

// True relative length change of the skin segment whose ends are at image positions a_from and
// b_from in frame_from, when seen again in frame_to: (|b'-a'| - |b-a|) / |b-a|.
double true_rel_change(const SceneSpec& spec, PointMm a_from, PointMm b_from, int frame_from,
                       int frame_to);

// Whether the skin at this image position touches the glass (and so is imaged) in `frame`.
bool in_contact(const SceneSpec& spec, PointMm image, int frame);

// The true calibration of the synthetic camera.
Calibration true_calibration(const SceneSpec& spec);

SyntheticSequence render_sequence(const SceneSpec& spec,
                                  const std::function<void(int done, int total)>& progress = {});

// Writes frame_000.png ..., calibration/dot_grid.png, landmarks.csv and scene.json (spec,
// calibration and provenance: no input, method "synthetic scene", the spec as parameters, and
// `command_line`). Only the frames are images at the top level, so DIR is a valid capture input.
void write_sequence(const std::filesystem::path& dir, const SyntheticSequence& sequence,
                    const std::string& command_line = {});

// landmarks.csv: id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm, one row per landmark and frame.
void write_landmarks_csv(const std::filesystem::path& path,
                         const std::vector<TruthLandmark>& landmarks);

}  // namespace tactile::capture
