#pragma once
// A field drawn beside the contactor array in the viewer, e.g. the strain movie a tactile movie
// was mapped from. Plain data: display knows nothing of strain; the caller (tools/tactile)
// turns its field into segments with one signed value each, and the viewer draws them from
// black (-full_scale: most compressed) through grey to white (+full_scale: most stretched),
// the rule of capture's strain maps.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/movie/frame_geometry.hpp"

namespace tactile::movie {

struct FieldSegment {
  double x0_mm = 0;
  double y0_mm = 0;
  double x1_mm = 0;
  double y1_mm = 0;
  double value = 0;  // e.g. relative change of an edge's length
};

struct FieldFrame {
  double t_s = 0;  // movie time at which this frame starts to show (0 = the movie's first frame)
  std::vector<FieldSegment> segments;
};

struct SideField {
  std::string title;      // one line, shown above the field
  double full_scale = 0;  // |value| drawn pure black / white; must be > 0
  double width_mm = 0;    // extent of the field, from (0, 0)
  double height_mm = 0;
  std::vector<FieldFrame> frames;  // increasing t_s
};

// Grey level of a value: 0 at -full_scale, 128 at 0, 255 at +full_scale, saturating.
std::uint8_t field_grey(double value, double full_scale);

// The frame to show at movie time t_s: the last one starting at or before it (the first one
// before any starts). Throws std::invalid_argument for a field without frames.
std::size_t field_frame_at(const SideField& field, double t_s);

// Placement of the field in a w x h pixel area (y down), uniform scale, 6 % margin.
ViewTransform fit_field(const SideField& field, int width_px, int height_px);

// Throws std::invalid_argument naming what is wrong: no frames, a non-positive or non-finite
// full scale or extent, times not increasing, non-finite coordinates.
void validate_side_field(const SideField& field);

}  // namespace tactile::movie
