#pragma once
// Where the skin touches the glass in each camera frame, measured from the images alone.
//
// Skin seen through the glass shows its ridges only where it touches; out of contact it is bright
// and even (a prism's frustrated reflection, or the glass's own focus). The view is cut into
// square cells of about a millimetre, and a cell's ridge contrast is the RMS of its image minus
// the image's local mean over one ridge period. A cell is in contact when its contrast reaches a
// fraction of the contrast of skin in contact in the same sequence, so that the rule follows the
// camera's exposure and the print's depth rather than a grey level fixed in advance.

#include <cstdint>
#include <vector>

#include "tactile/capture/image.hpp"

namespace tactile::capture {

// The cells of a view: `cell_px` square, the last column and row cut by the image's edge.
struct ContactGrid {
  std::int32_t cell_px = 0;
  std::int32_t columns = 0;
  std::int32_t rows = 0;

  std::int32_t cells() const { return columns * rows; }
};

struct ContactMap {
  ContactGrid grid;  // cell_px 0: no contact was measured (a file written without it)
  // Grey levels: a cell whose ridge contrast is at least this is in contact.
  double threshold = 0;
  // Per camera frame, grid.rows x grid.columns, row-major: the cell's ridge contrast (RMS, grey
  // levels) and whether it is in contact (1) or not (0).
  std::vector<double> ridge_contrast;
  std::vector<std::uint8_t> in_contact;
  // A map measured as the frames came (a live session), else both empty. Each frame was judged
  // by the threshold of the frames seen up to it (frame_threshold, grey levels; `threshold` is
  // then unused), and a frame the session dropped unseen has frame_seen 0 and cells of contrast
  // 0, out of contact: they say nothing of the skin.
  std::vector<double> frame_threshold;
  std::vector<std::uint8_t> frame_seen;

  bool measured() const { return grid.cell_px > 0; }
  bool per_frame() const { return !frame_threshold.empty(); }
  // Whether camera frame `frame` was measured (every frame of a map measured in one piece).
  bool seen(std::int32_t frame) const {
    return frame_seen.empty() ||
           (frame >= 0 && static_cast<std::size_t>(frame) < frame_seen.size() &&
            frame_seen[static_cast<std::size_t>(frame)] != 0);
  }
  std::int32_t frame_count() const {
    return grid.cells() > 0 ? static_cast<std::int32_t>(in_contact.size()) / grid.cells() : 0;
  }
};

// The contact threshold as a fraction of the contrast of skin in contact (the 90th percentile of
// every cell's contrast in the sequence): ridges that lose contact fade to the even brightness of
// the valleys, so half contact lies near half the contrast, and 0.4 keeps a cell whose ridges are
// merely fainter (a lighter touch, a drier finger) in contact. Below kContactFloorGrey a cell is
// even to the eye whatever the sequence: camera noise alone (an RMS of 2-3 grey levels in the
// synthetic scenes and the cameras here) stays under it, and ridges in contact reach 20-40.
constexpr double kContactFraction = 0.4;
constexpr double kContactFloorGrey = 5.0;

// Cells of about a millimetre (at least 8 px, at most 256) over a width x height image.
ContactGrid contact_grid(int width_px, int height_px, double px_per_mm);

// Cells of `cell_px` over a width x height image (as a file names them), the last column and row
// cut by the image's edge.
ContactGrid contact_grid_of_cells(int width_px, int height_px, std::int32_t cell_px);

// Each cell's ridge contrast in one frame (grid.rows x grid.columns, row-major). The frame must
// be the grid's image size.
std::vector<double> cell_ridge_contrast(const GrayImage& frame, const ContactGrid& grid,
                                        double px_per_mm);

// The map of a whole sequence from every frame's cell contrasts, one after the other: the
// threshold from the sequence (kContactFraction, kContactFloorGrey) and each cell's contact.
ContactMap contact_map(const ContactGrid& grid, std::vector<double> ridge_contrast);

// The map of a sequence held in memory (frames of one size; none gives an unmeasured map).
ContactMap measure_contact(const std::vector<GrayImage>& frames, double px_per_mm);

// The contact of frames as they come, for a session that cannot wait for the whole sequence: the
// threshold is kContactFraction of the contrast of skin in contact seen so far (the highest 90th
// percentile of one frame's cell contrasts), at least kContactFloorGrey. A frame mostly out of
// contact lowers nothing; the first frame that shows skin in contact sets the scale.
struct RunningContact {
  double contact_contrast_grey = 0;
};

// The threshold of the frames seen so far, grey levels.
double running_threshold_grey(const RunningContact& running);

// One frame's cells (its cell_ridge_contrast): 1 in contact, 0 not, by the threshold of the
// frames seen so far, this one included (`running` is updated).
std::vector<std::uint8_t> contact_of_frame(RunningContact& running,
                                           const std::vector<double>& ridge_contrast);

// The fraction of cells in contact in camera frame `frame` (0 when the map has no such frame or
// did not see it).
double contact_fraction(const ContactMap& map, std::int32_t frame);

}  // namespace tactile::capture
