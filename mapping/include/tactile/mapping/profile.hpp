#pragma once
// Method "profile": model-driven rendering of a surface under a moving finger, the way tactile
// graphics and virtual Braille are rendered on Latero-class displays. No strain is measured:
// each contactor deflects against the local slope of a height map at the point of the surface
// it is over,
//   d = -gain_um_per_slope * dh/ds,   s = the deflection axis,
// which is the lateral-force illusion of shape (Robles-De-La-Torre & Hayward 2001: a lateral
// force resisting the finger on the way up a slope and helping it down is felt as a bump). The
// contactor grid rides with the finger (the finger rests on the display), centred on the finger;
// the finger moves at constant velocity over the surface. Movies of this method are directly
// comparable with measurement-driven ones of the same scene (experiments run both).

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/capture/synth.hpp"
#include "tactile/common/names.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// "bump" (Gaussian up), "hole" (Gaussian down), "flat".
enum class ProfileShape { bump, hole, flat };
inline constexpr std::array<Named<ProfileShape>, 3> kProfileShapeNames = {{
    {ProfileShape::bump, "bump"},
    {ProfileShape::hole, "hole"},
    {ProfileShape::flat, "flat"},
}};
inline constexpr auto kProfileShapes = values_of(kProfileShapeNames);
std::string to_string(ProfileShape shape);
// Throws std::invalid_argument naming the bad name and the accepted ones.
ProfileShape parse_profile_shape(std::string_view name);

struct SurfaceProfile {
  ProfileShape shape = ProfileShape::bump;
  double height_mm = 0.5;   // bump height or hole depth
  double width_mm = 3.0;    // full width at half maximum
  double feature_x_mm = 0;  // feature centre on the surface
  double feature_y_mm = 0;
  double finger_x0_mm = 0;  // finger (grid centre) over the surface at t = 0
  double finger_y0_mm = 0;
  double velocity_x_mm_per_s = 2.4;
  double velocity_y_mm_per_s = 0;
};

// The surface and finger path of a synthetic scene (capture::SceneSpec): the feature at the
// image centre, the finger's path centred on it, its speed along +x. Image coordinates serve as
// surface coordinates (the camera is fixed to the glass).
SurfaceProfile profile_of_scene(const capture::SceneSpec& spec);

// Height (mm) and its gradient at a surface point.
double profile_height_mm(const SurfaceProfile& profile, double x_mm, double y_mm);
capture::PointMm profile_gradient(const SurfaceProfile& profile, double x_mm, double y_mm);

// One frame at time t_s, row-major, before normalisation and limits. Throws
// std::invalid_argument for a non-positive width.
std::vector<double> profile_frame(const SurfaceProfile& profile, const movie::Layout& layout,
                                  double t_s, double gain_um_per_slope);

}  // namespace tactile::mapping
