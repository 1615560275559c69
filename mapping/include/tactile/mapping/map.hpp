#pragma once
// Strain movie -> tactile movie, the whole mapping in one call:
//   0. strain "per-frame" takes the StrainFrames as the capture made them (frame-to-frame or
//      span-k); strain "accumulated" first turns the tracks into strain from a reference frame
//      (accumulate.hpp, Lagrangian);
//   1. one StrainField per StrainFrame (strain_field.hpp);
//   2. a mapping method turns each field into contactor deflections at the camera frame's time
//      (methods.hpp), sampled where the placement puts the contactors (placement.hpp);
//   3. normalisation (gain policy, below);
//   4. linear resampling from the camera frame times to rate_hz (resample.hpp);
//   5. clamp to the layout's deflection range and slew-rate limit (limits.hpp).

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/names.hpp"
#include "tactile/mapping/accumulate.hpp"
#include "tactile/mapping/limits.hpp"
#include "tactile/mapping/placement.hpp"
#include "tactile/mapping/profile.hpp"
#include "tactile/mapping/strain_field.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// "proportional" or "integrated" (see methods.hpp), or "profile" (profile.hpp: model-driven,
// needs MappingParams::profile; the strain frames then only give the times, and the gain is
// micrometres per unit slope).
enum class MappingMethod { proportional, integrated, profile };
// "none": deflections are gain * strain as they come. "peak": after the method, every deflection
// is rescaled by one factor so that the movie's largest |deflection| equals peak_fraction of the
// smaller side of the layout's deflection range (then the gain's magnitude does not matter).
// "p99": the same with the 99th percentile of the non-zero |deflections| in place of the largest,
// so that a few outliers of a noisy measurement do not shrink the whole movie (the top percent
// then clamps).
enum class Normalisation { none, peak, p99 };
// "per-frame": the strain movie's own StrainFrames. "accumulated": strain from
// accumulate.reference_frame to each later frame along the tracks (accumulate.hpp).
enum class StrainMode { per_frame, accumulated };

// The names written in files and accepted on the command line and in experiment files.
inline constexpr std::array<Named<MappingMethod>, 3> kMappingMethodNames = {{
    {MappingMethod::proportional, "proportional"},
    {MappingMethod::integrated, "integrated"},
    {MappingMethod::profile, "profile"},
}};
inline constexpr std::array<Named<Normalisation>, 3> kNormalisationNames = {{
    {Normalisation::none, "none"},
    {Normalisation::peak, "peak"},
    {Normalisation::p99, "p99"},
}};
inline constexpr std::array<Named<StrainMode>, 2> kStrainModeNames = {{
    {StrainMode::per_frame, "per-frame"},
    {StrainMode::accumulated, "accumulated"},
}};
inline constexpr auto kMappingMethods = values_of(kMappingMethodNames);
inline constexpr auto kNormalisations = values_of(kNormalisationNames);
inline constexpr auto kStrainModes = values_of(kStrainModeNames);

// The parsers throw std::invalid_argument naming the bad name and the accepted ones.
std::string to_string(MappingMethod method);
std::string to_string(Normalisation normalisation);
std::string to_string(StrainMode strain);
MappingMethod parse_mapping_method(std::string_view name);
Normalisation parse_normalisation(std::string_view name);
StrainMode parse_strain_mode(std::string_view name);

struct MappingParams {
  // "integrated" by default: its neighbouring contactors impose the measured strain on the finger
  // (correlation 1.000 with the source strain on the ground-truth scenes of
  // tools/experiments/methods.json), while "proportional" deflects each contactor by the local
  // strain and imposes something else (correlation 0.02 to 0.05 there); docs/architecture.md.
  MappingMethod method = MappingMethod::integrated;
  std::optional<SurfaceProfile> profile;
  // Micrometres of deflection per unit strain (for "integrated": per millimetre of pitch, so 1000
  // reproduces the skin's extension). 1000 um per unit strain = 1 um per 0.1 % strain.
  double gain_um_per_strain = 1000.0;
  Normalisation normalisation = Normalisation::none;
  double peak_fraction = 1.0;
  // Display frame rate; unset = the layout's own rate (layout.max_rate_hz), so every caller
  // (map, demo, experiments) maps a layout at the same rate unless told otherwise.
  std::optional<double> rate_hz;
  StrainMode strain = StrainMode::per_frame;
  AccumulateOptions accumulate;
  // Where the contactor grid sits on the field; unset = default_placement(movie).
  std::optional<Placement> placement;
  double slew_limit_um_per_s = movie::kDefaultSlewLimitUmPerS;
  StrainFieldOptions field;
  // Recorded in the provenance; empty = this library's version.
  std::string program_version;
};

// The parameters a mapping onto `layout` uses: the rules every caller shares, in one place.
// Fills the defaults that depend on the layout (rate_hz unset -> layout.max_rate_hz) and checks
// everything before any work: non-positive or non-finite gain, slew limit or scale,
// peak_fraction outside (0, 1], a rate above layout.max_rate_hz or not playable
// (movie::kPlayableRateRule: a movie a device cannot play is refused when it is made), a layout
// without contactors. Throws std::invalid_argument naming the problem. The result has rate_hz set.
MappingParams resolve_mapping_params(const MappingParams& params, const movie::Layout& layout);

// The parameters as a JSON object (stored in Provenance::mapping_parameters_json). The placement
// written is the one actually used; normalisation_factor is the factor "peak" or "p99" applied
// (1 = none).
std::string parameters_json(const MappingParams& params, const Placement& placement_used,
                            double normalisation_factor = 1.0);

struct MappingResult {
  movie::TactileMovie movie;
  Placement placement;              // the one used (params.placement or the default)
  double normalisation_factor = 1;  // applied by "peak" / "p99"; 1 for "none"
  // Deflection difference per unit strain per mm of pitch actually used by "integrated", and
  // deflection per unit strain for "proportional": gain_um_per_strain * normalisation_factor.
  double um_per_strain = 0;
};

// The strain movie the mapping reads for these parameters: `movie` itself for strain
// "per-frame", accumulate_along_tracks(movie, params.accumulate) for "accumulated".
capture::StrainMovie strain_source(const capture::StrainMovie& movie, const MappingParams& params);

// Maps the StrainFrames of `source` as they are (params.strain is only recorded: pass the
// movie strain_source() returned), and says what placement and scale it used.
MappingResult map_strain_frames(const capture::StrainMovie& source, const movie::Layout& layout,
                                const MappingParams& params);

// Maps the strain movie onto the layout: map_strain_frames(strain_source(movie, params), ...).
// Throws std::invalid_argument for bad parameters (see resolve_mapping_params), an empty strain
// movie, or strain frame times that do not increase. The provenance gets the method, its
// parameters, the program version and the time; the input (the strain movie's file) is left to the
// caller.
movie::TactileMovie map_strain_movie(const capture::StrainMovie& movie, const movie::Layout& layout,
                                     const MappingParams& params);

}  // namespace tactile::mapping
