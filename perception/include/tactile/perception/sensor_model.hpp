#pragma once
// A simple simulated BioTac-style fingertip (docs/perception-models.md): an elastic pad, locally
// indented by the plate (Winkler foundation, saturating at the fluid layer's thickness) under a
// skin that cannot curve more sharply than its minimum bending radius; fluid pressure follows
// the displaced volume, each electrode's impedance the indentation, bending and stretch of the
// skin over its receptive field, and vibration the AC-coupled rate of change of the load plus
// skin ringing and sliding-friction noise. Output is a SensorRecording in integer raw counts,
// like a real recording.

#include <array>
#include <cstdint>

#include "tactile/common/names.hpp"
#include "tactile/perception/recording.hpp"
#include "tactile/perception/sensor_scene.hpp"

namespace tactile::perception {

// Scales of the trial-to-trial variation drawn by draw_variation, each relative to the spreads
// documented in docs/perception-models.md (1 = as documented, 0 = none): where the arm puts the
// finger (the feature's position and the contact angle), the commanded depth, and the speed.
struct VariationScale {
  double position = 1.0, depth = 1.0, speed = 1.0;
};

// How an electrode weighs the skin around it (docs/perception-models.md): `gaussian`, its face
// and a margin about the gap's thickness (sigma electrode_field_mm); `sheet`, the fluid as a thin
// conducting sheet, in which a change of the gap at distance r weighs as 1 / r^2 out to
// sheet_reach_mm (1 / face^2 over the face of radius sheet_face_mm).
enum class ElectrodeField { gaussian, sheet };
inline constexpr std::array<Named<ElectrodeField>, 2> kElectrodeFieldNames = {{
    {ElectrodeField::gaussian, "gaussian"},
    {ElectrodeField::sheet, "sheet"},
}};

struct SensorModel {
  double pad_radius_x_mm = 15.0;  // curvature of the pad along the finger (distal-proximal)
  double pad_radius_y_mm = 8.0;   // across the finger (radial-ulnar)
  double depth_transfer = 0.3;    // fraction of the commanded depth that indents the pad
  double fluid_layer_mm = 3.0;    // indentation saturates here (skin meets the core)
  double pressure_baseline = 2000, pressure_per_mm3 = 3.0, pressure_noise = 0.5;
  double electrode_baseline = 3000, electrode_per_mm = 80.0, electrode_noise = 0.8;
  double electrode_per_bending_mm = 1000.0;  // counts per 1/mm of skin curvature at an electrode
  double electrode_per_strain = 10000.0;  // counts per unit stretch of the skin over an electrode
  double electrode_field_mm = 0.4;  // sigma of an electrode's receptive field (face + gap margin)
  int electrode_field_samples = 9;  // grid points across the field (odd), out to 2 sigma
  ElectrodeField electrode_field = ElectrodeField::gaussian;
  double sheet_face_mm = 0.5, sheet_reach_mm = 3.0;  // ElectrodeField::sheet (assumed)
  double skin_bend_radius_mm = 0.1;                  // the skin cannot curve more sharply than this
  double vibration_offset = 2048, vibration_gain = 0.4, vibration_noise = 4.0;
  double edge_gain = 50.0;  // skin ringing kick per unit change of slope (SkinRinging; assumed)
  double friction_noise_per_unit = 0.02;  // sliding noise per pressure count per mm/s
  double baseline_spread = 20.0;          // trial-to-trial spread of baselines (counts)
  VariationScale variation;               // trial-to-trial variation (draw_variation)
};

// x (distal +) and y (ulnar +) of the 19 electrodes on the pad, mm from its centre.
struct PadPoint {
  double x_mm, y_mm;
};
std::array<PadPoint, kElectrodeCount> sensor_electrode_positions();

// Draws the trial-to-trial variation of trial `seed` (deterministic).
TrialVariation draw_variation(std::uint64_t seed, const VariationScale& scale = {});

SensorRecording simulate_trial(const SurfaceFeature& feature, Procedure procedure,
                               std::uint64_t seed, const SensorModel& model = {});

}  // namespace tactile::perception
