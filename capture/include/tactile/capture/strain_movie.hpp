#pragma once
// Plain data that leaves the capture module: what the camera pipeline measured.
// Positions are millimetres in the calibrated image plane (x right, y down as seen by the camera).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/capture/contact_map.hpp"
#include "tactile/common/provenance.hpp"

namespace tactile::capture {

// The prism camera's frame rate in the first paper (640 x 484 at 60 Hz): the rate of a sequence
// whose rate nobody stated, and of the synthetic scenes.
inline constexpr double kCameraRateHz = 60.0;

enum class FeatureType : std::uint8_t { pore = 0, ending = 1, bifurcation = 2 };

// Name used in CSV files and HDF5 attributes ("pore", "ending", "bifurcation").
const char* feature_type_name(FeatureType type);
// Inverse of feature_type_name; throws std::invalid_argument naming the bad text.
FeatureType parse_feature_type(const std::string& name);

// Pixel <-> millimetre mapping of one camera. mm = H * [x_px, y_px, 1] (homogeneous).
struct Calibration {
  std::array<double, 9> px_to_mm{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major 3x3 homography
  double mm_per_px = 1.0;  // mean scale, for converting lengths such as blob areas
  int image_width_px = 0;
  int image_height_px = 0;
  std::string method;  // how it was obtained, e.g. "dot-grid 0.5 mm" or "px-per-mm 47"
};

struct PointMm {
  double x_mm = 0;
  double y_mm = 0;
};

PointMm to_mm(const Calibration& calibration, double x_px, double y_px);
Calibration uniform_calibration(double px_per_mm, int width_px, int height_px);

// Throws std::invalid_argument when the calibration names an image size (non-zero) other than
// width_px x height_px: its mapping is for another camera or another crop. `calibration_source`
// and `image_source` name the two in the message (e.g. the files).
void check_calibration_fits(const Calibration& calibration, int width_px, int height_px,
                            const std::string& calibration_source, const std::string& image_source);

// A landmark found in one image.
struct Feature {
  FeatureType type = FeatureType::pore;
  double x_px = 0;
  double y_px = 0;
  double orientation_rad = 0;  // minutia direction; 0 for pores
};

// One landmark of one track at one frame (smoothed position).
struct TrackedPoint {
  std::int32_t track_id = 0;
  std::int32_t frame = 0;
  FeatureType type = FeatureType::pore;
  double x_px = 0;
  double y_px = 0;
  double x_mm = 0;
  double y_mm = 0;
};

// An edge of the Delaunay triangulation of the landmarks tracked from frame_from to frame_to.
struct StrainEdge {
  std::int32_t track_a = 0;
  std::int32_t track_b = 0;
  double length_from_mm = 0;
  double length_to_mm = 0;
  double rel_change = 0;  // (length_to - length_from) / length_from
};

// A triangle of the same triangulation, as indices into StrainFrame::points.
struct StrainTriangle {
  std::array<std::int32_t, 3> point_index{0, 0, 0};
};

// Strain between two camera frames: the tracked points at frame_from, and the edges/triangles of
// their triangulation with each edge's relative length change at frame_to.
struct StrainFrame {
  std::int32_t frame_from = 0;
  std::int32_t frame_to = 0;
  double t_s = 0;  // time of frame_to
  std::vector<TrackedPoint> points_from;
  std::vector<TrackedPoint> points_to;  // same order and track ids as points_from
  std::vector<StrainEdge> edges;
  std::vector<StrainTriangle> triangles;
};

struct StrainMovie {
  double frame_rate_hz = kCameraRateHz;
  std::int32_t span_frames = 1;  // frame_to - frame_from for every StrainFrame
  std::int32_t camera_frame_count = 0;
  double field_width_mm = 0;
  double field_height_mm = 0;
  Calibration calibration;
  Provenance provenance;  // what it was measured from, how and by which program
  // Every smoothed point of every kept track, ordered by track, then frame.
  std::vector<TrackedPoint> tracks;
  std::vector<StrainFrame> frames;
  // Where the skin touched in each camera frame (not measured: grid.cell_px 0).
  ContactMap contact;
};

}  // namespace tactile::capture
