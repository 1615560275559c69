#pragma once
// Strain only where the skin touched the glass. Skin out of contact shows no ridges, so nothing
// can be tracked on it, and at the rim of such a region the ridges fade: points there are found
// and followed less surely, and an edge between two of them reports strain that the skin does
// not have. The contact map (contact_map.hpp) says, from the images alone, which cells touched in
// each camera frame; the strain measured at or beside a cell that did not is left out.

#include <cstdint>
#include <span>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {

// How far from a cell out of contact strain is still left out, in cells (about a millimetre
// each): one cell holds the rim, where ridges fade over a ridge period or two.
constexpr std::int32_t kGapMarginCells = 1;

// Whether the capture found the skin sliding through the view (its provenance's
// `frames_in_view`, from the registration of whole frames).
bool skin_slides_through_view(const StrainMovie& movie);

// The strain a capture reports. Where the skin slides through the view, it crosses the rim of
// any region out of contact, and tracks there follow skin that is leaving or landing: the movie
// loses the strain at or within kGapMarginCells of skin out of contact, and, because the
// capture smooths each track over the frames on either side (its provenance's
// `smoothing_half_window_used`), the strain of a track within that many frames of such a
// moment too. In a still contact the rim holds the same skin, which tracks as well as any, and
// the movie is kept as measured (with the margin, one synthetic bump scene lost 57 % of its
// edges and 0.002 of correlation).
StrainMovie strain_in_contact(StrainMovie movie);

// The movie without the edges and triangles that have an end on a track that was in a cell out
// of contact, or within `margin_cells` of one, in a camera frame from `window_frames` before the
// strain frame's first camera frame to `window_frames` after its last. The points stay
// (triangles index them). A movie without a contact map is returned as it is.
StrainMovie without_strain_near_gaps(StrainMovie movie, std::int32_t margin_cells = kGapMarginCells,
                                     std::int32_t window_frames = 0);

// The tracks that never stood in a cell out of contact, or within `margin_cells` of one, in any
// camera frame the map saw. A map that was not measured keeps every track.
std::vector<Track> tracks_clear_of_gaps(const std::vector<Track>& tracks, const ContactMap& map,
                                        std::int32_t margin_cells = kGapMarginCells);

// One camera frame's cells (grid.rows x grid.columns, row-major, 1 in contact): 1 where a cell is
// out of contact or within `margin_cells` of one.
std::vector<std::uint8_t> cells_near_gap(const ContactGrid& grid,
                                         std::span<const std::uint8_t> in_contact,
                                         std::int32_t margin_cells = kGapMarginCells);

// A strain frame measured from one camera frame straight to the next, as a causal tracker does
// (nothing smoothed across frames): its edges and triangles with an end on a point that stood in a
// cell `near_from` marks (in the frame it is measured from) or `near_to` marks (in the frame it is
// measured to) left out; the points stay. Returns how many edges were left out.
std::int64_t leave_out_strain_near_gaps(StrainFrame& frame, const ContactGrid& grid,
                                        std::span<const std::uint8_t> near_from,
                                        std::span<const std::uint8_t> near_to);

}  // namespace tactile::capture
