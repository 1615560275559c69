#pragma once
// The contact mechanics of the simulated fingertip, for models that need more than the sensor's
// channels (sensor_strain.cpp: the skin's strain). Private to capture.
//
// The kinematics, displaced volume and arm balance are those the sensor's channels use
// (sensor_model.cpp calls these), so the skin strain and the sensor see the same trial.

#include <vector>

#include "tactile/perception/sensor_model.hpp"
#include "tactile/perception/sensor_scene.hpp"

namespace tactile::perception::contact {

// One step of a trial: indentation depth, where the pad's contact centre is and where the
// feature's centre is, both in pad coordinates (mm, x distal, y ulnar), and the sliding speed.
struct Pose {
  double depth_mm = 0;  // plan: commanded descent; after balance: pad indentation
  double contact_x_mm = 0, contact_y_mm = 0;
  double feature_x_mm = 0, feature_y_mm = 0;
  double slide_mm_s = 0;
};

// The commanded motion of a trial sampled at rate_hz (docs/perception-models.md, "Scenes").
std::vector<Pose> plan(Procedure procedure, const TrialVariation& v, const SensorModel& m,
                       double rate_hz);

// Indentation of the pad at pad point (x, y), saturating at the fluid layer's thickness.
double indentation_mm(const SurfaceFeature& f, const Pose& p, const SensorModel& m, double x,
                      double y);

// Displaced volume (mm^3) of the pad at pose p: the flat plate's paraboloid cap plus the feature's
// extra volume (negative for pits), never below zero.
double displaced_volume_mm3(const SurfaceFeature& f, const Pose& p, const SensorModel& m);

// Arm stiffness (mm^3 of displaced volume per mm of arm compression) for which a flat plate
// indents the pad by depth_transfer of the commanded depth.
double arm_stiffness(Procedure procedure, const SensorModel& m);

// Pad indentation where the arm's spring balances the pad's displaced volume, two Newton steps
// from `depth` (the previous step's), so the finger follows a moving balance.
double balance_depth(const SurfaceFeature& f, Pose p, double commanded_mm, double depth,
                     const SensorModel& m, double kappa);

}  // namespace tactile::perception::contact
