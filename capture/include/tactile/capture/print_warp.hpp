#pragma once
// Test sequences made from a real fingerprint image: the print is moved by a known smooth
// non-rigid warp (slide and rotation plus a local stretch, compression, radial bump or
// travelling strain wave), and each frame is filmed with camera blur, noise and a brightness
// drift. The warp is exact, so the strain of every segment is known: `tactile evaluate` scores a
// strain movie of such a sequence as it scores the synthetic scenes.
//
// Kinematics: a material point X (millimetres on the source print, origin at its top-left pixel
// centre) is seen at frame f at
//   x = c + R(theta(f)) (X + u(X, f) - c) + s(f)
// where c is the image centre, R a rotation, s a slide (both growing linearly over the
// sequence) and u the pattern's displacement, whose strain rises and falls back as
// sin(pi f / (frames - 1)).
//
// Full slip is the exception: the skin slides along x at the travel speed, x = c + p + w(p) with
// p = X - c + v t ex, and w a static smooth displacement field of the glass's frame (Gaussian
// kernels), so each skin element is strained as it crosses the contact, as skin is in steady
// sliding. Rotation and the sequence's slide are not used. The source print's touched area (its
// edges cut where the ridges fade out: a border the finger did not touch) is mirrored at its
// borders without end, so the skin may travel many view widths.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/names.hpp"

namespace tactile::capture {

enum class WarpPattern {
  rigid,       // slide and rotation only: every true strain is zero
  stretch,     // local uniaxial stretch along x (Gaussian envelope)
  compress,    // local uniaxial compression along y (Gaussian envelope)
  bump,        // radial stretch at the centre, compression around it (as a bump pushes skin)
  wave,        // a strain wave along x travelling one wavelength over the sequence
  pulse,       // a bump of radial strain crossing the field along x
  ridge,       // a ridge of compression along x, ahead of a sliding edge, crossing the field
  stick_slip,  // a slipping rim around a sticking centre: slow loading, sudden partial slip
  kernels,     // a random smooth field: several Gaussian displacement kernels, own time courses
  full_slip,   // the skin slides through the view at the travel speed, strained by a field
               // fixed on the glass (the print mirrored without end, so it can travel far)
};

inline constexpr std::array<Named<WarpPattern>, 10> kWarpPatternNames = {{
    {WarpPattern::rigid, "rigid"},
    {WarpPattern::stretch, "stretch"},
    {WarpPattern::compress, "compress"},
    {WarpPattern::bump, "bump"},
    {WarpPattern::wave, "wave"},
    {WarpPattern::pulse, "pulse"},
    {WarpPattern::ridge, "ridge"},
    {WarpPattern::stick_slip, "stick-slip"},
    {WarpPattern::kernels, "kernels"},
    {WarpPattern::full_slip, "full-slip"},
}};
WarpPattern parse_warp_pattern(std::string_view name);  // throws std::invalid_argument
std::string to_string(WarpPattern pattern);

struct PrintWarpSpec {
  std::string source;  // the print's file name, for the record
  double px_per_mm = 47.0;
  int width_px = 0;  // the source print's size (the camera sees the same field)
  int height_px = 0;
  WarpPattern pattern = WarpPattern::wave;
  double strain = 0.04;      // peak strain of the pattern (0.04 = 4 %)
  double width_mm = 3.0;     // Gaussian envelope's full width at half maximum; wave's length
  double slide_x_mm = 0.25;  // rigid slide over the whole sequence
  double slide_y_mm = 0.08;
  double rotation_deg = 1.5;  // rigid rotation over the whole sequence
  int frame_count = 30;
  double frame_rate_hz = kCameraRateHz;
  // Motion in physical units: with travel_speed_mm_per_s > 0 the travelling patterns (wave,
  // pulse, ridge) cross the field at that speed and the stick-slip and kernel patterns change on
  // the time the skin takes to travel the pattern's width; with 0 each takes the whole sequence.
  // Full slip: the skin's speed through the view (must be > 0).
  double travel_speed_mm_per_s = 0;
  double exposure_s = 0;  // shutter open time, centred on each frame's instant (motion blur)
  // Samples per pixel side: each pixel integrates the moving image over its area (and, with an
  // exposure, over the shutter time), as a sensor does.
  int supersample = 1;
  // Peak strength of a region that loses contact (shown as bright skin, its pores not in the
  // truth) in the middle of the sequence and regains it; 0 = none, 1 = fully lifted.
  double contact_loss = 0;
  // A contact patch smaller than the view, an ellipse of semi-axes 0.4 x the view's width and
  // height: skin outside it is out of contact (bright, its pores not in the truth). It moves
  // along x at patch_speed_mm_per_s (centred in the view mid-sequence) and its semi-axes grow
  // and shrink by the fraction patch_breathing, one cycle over the sequence. No patch (the whole
  // view in contact) while both are 0.
  double patch_speed_mm_per_s = 0;
  double patch_breathing = 0;
  double blur_sigma_px = 0.7;
  double noise_sigma = 2.0;        // grey levels, new in every frame
  double brightness_drift = 0.06;  // relative change of exposure from first to last frame
  std::uint64_t seed = 1;
};

// Throws std::invalid_argument naming the first bad field (strain above 0.2 would fold the
// Gaussian patterns; the fixed-point inversion of the warp needs its gradient below 1).
void validate_print_warp(const PrintWarpSpec& spec);

// Seconds from the first frame to the last.
double sequence_duration_s(const PrintWarpSpec& spec);

// Image millimetres at `frame` of a material point, and its inverse. `frame` may be fractional
// (an instant within the exposure).
PointMm warp_to_image(const PrintWarpSpec& spec, PointMm material, double frame);
PointMm warp_to_material(const PrintWarpSpec& spec, PointMm image, double frame);

// Whether the skin touches in a patch smaller than the view (patch_speed or patch_breathing).
bool has_contact_patch(const PrintWarpSpec& spec);

// How much of the skin seen at image point `image` touches the glass at `frame`, 0..1.
double warp_contact(const PrintWarpSpec& spec, PointMm image, double frame);

// The least contact anywhere in the view at `frame` (sampled every `step_px` pixels, 0..1).
double warp_least_contact(const PrintWarpSpec& spec, double frame, int step_px);

// True relative length change of the segment seen at a_from, b_from (image millimetres) in
// frame_from, when seen again in frame_to.
double warp_rel_change(const PrintWarpSpec& spec, PointMm a_from, PointMm b_from, int frame_from,
                       int frame_to);

struct PrintSequence {
  PrintWarpSpec spec;
  Calibration calibration;  // uniform px_per_mm
  std::vector<GrayImage> frames;
  // Hand-marked pores of the source print (0-based x, y pixels; empty when none were given),
  // written through the warp as the sequence's landmarks, ids in the order of the marks.
  std::vector<std::array<double, 2>> marks_px;
  std::vector<TruthLandmark> landmarks;  // the marks in view, every frame (pores, id = mark index)
};

// Renders the sequence (marks_px as in PrintSequence; read them with read_pore_marks).
// Throws std::invalid_argument for a bad spec or a print whose size is not the spec's.
PrintSequence render_print_sequence(const PrintWarpSpec& spec, const GrayImage& print,
                                    const std::vector<std::array<double, 2>>& marks_px = {});

// frame_NNN.png, landmarks.csv (the marks through the warp) and scene.json (format
// tactile-print-warp: the spec, the calibration and the provenance: input `print`, method "print
// warp", the spec as parameters, and `command_line`), so that DIR is a `tactile capture` input
// and a `tactile evaluate` ground truth.
void write_print_sequence(const std::filesystem::path& dir, const PrintSequence& sequence,
                          const std::filesystem::path& print = {},
                          const std::string& command_line = {});

}  // namespace tactile::capture
