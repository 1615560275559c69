#pragma once
// Scenes of paper 2: the feature plates and the exploratory procedures with their kinematics.
// Assumptions in docs/perception-models.md.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile::perception {

// Order of curvature of a feature's profile: planar (flat top / floor), conical, spherical.
enum class Curvature { planar = 0, conical = 1, spherical = 2 };

struct SurfaceFeature {
  Curvature curvature = Curvature::planar;
  double footprint_mm = 5.0;  // diameter at the plate surface
  double height_mm = 2.5;     // > 0 bump, < 0 pit
  double signed_footprint_mm() const { return height_mm > 0 ? footprint_mm : -footprint_mm; }
  // Height of the surface (mm) at distance r_mm from the feature's centre.
  double surface_mm(double r_mm) const;
};

// The 48 features: 3 curvatures x bump/pit x footprints 1.25, 2.5, 3.75, 5, 7.5, 10, 15, 20 mm;
// the five largest 2.5 mm high/deep, the three smallest half their footprint.
std::vector<SurfaceFeature> paper_features();

enum class Procedure { static_contact = 0, distal_proximal = 1, radial_ulnar = 2, roll = 3 };
inline constexpr int kProcedureCount = 4;
std::string procedure_name(Procedure p);  // "static", "distal-proximal", "radial-ulnar", "roll"
std::string procedure_short_name(Procedure p);  // "static", "dp", "ru", "roll" (input names)

// Commanded motion of one trial, before trial-to-trial variation.
struct ProcedureKinematics {
  double contact_angle_deg = 25.0;   // finger pad against the plate (30 for roll)
  double commanded_depth_mm = -5.5;  // below first contact
  double approach_s = 0.3;           // press (and release) ramps
  double hold_s = 1.5;               // static contact; strokes and roll last as long as motion
  double speed_mm_s = 10.0;          // strokes: 1 cm/s
  double stroke_mm = 30.0;           // strokes: centred on the feature
  double roll_deg = 45.0;            // roll about the finger's long axis
  double roll_s = 1.5;
  double rest_s = 0.5;  // free air before (baseline) and after contact
};
ProcedureKinematics paper_kinematics(Procedure p);

// Trial-to-trial variation of one trial (drawn from a seed by the sensor model).
struct TrialVariation {
  double offset_x_mm = 0, offset_y_mm = 0;  // feature centre vs commanded path
  double depth_scale = 1.0;
  double speed_scale = 1.0;
  double angle_deg = 0.0;
};

}  // namespace tactile::perception
