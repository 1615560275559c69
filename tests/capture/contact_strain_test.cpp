// Strain is left out at and beside skin out of contact, and only there.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tactile/capture/contact_strain.hpp"

namespace tactile::capture {
namespace {

TrackedPoint point(std::int32_t track, std::int32_t frame, double x_px, double y_px) {
  TrackedPoint p;
  p.track_id = track;
  p.frame = frame;
  p.x_px = x_px;
  p.y_px = y_px;
  return p;
}

// A 10 x 4 grid of 10 px cells over two camera frames, all in contact but cell (row 1, column
// 7) in frame `gap_frame`; one strain frame 0 -> 1 with a point in the middle of each cell of
// row 1 (track id = column), an edge between each pair of neighbours and a triangle over each
// three neighbours.
StrainMovie movie_with_a_gap(std::int32_t gap_frame) {
  StrainMovie m;
  m.camera_frame_count = 2;
  m.contact.grid = {10, 10, 4};
  m.contact.threshold = 5;
  m.contact.in_contact.assign(80, 1);
  m.contact.ridge_contrast.assign(80, 20);
  const std::size_t gap = static_cast<std::size_t>(gap_frame * 40 + 1 * 10 + 7);
  m.contact.in_contact[gap] = 0;
  m.contact.ridge_contrast[gap] = 1;
  StrainFrame f;
  f.frame_from = 0;
  f.frame_to = 1;
  for (std::int32_t c = 0; c < 10; ++c) {
    f.points_from.push_back(point(c, 0, 10 * c + 5, 15));
    f.points_to.push_back(point(c, 1, 10 * c + 5, 15));
  }
  for (std::int32_t c = 0; c + 1 < 10; ++c) f.edges.push_back({c, c + 1, 1, 1, 0});
  for (std::int32_t c = 0; c + 2 < 10; ++c) f.triangles.push_back({{c, c + 1, c + 2}});
  m.frames.push_back(f);
  return m;
}

std::vector<std::int32_t> edge_starts(const StrainFrame& f) {
  std::vector<std::int32_t> starts;
  for (const auto& e : f.edges) starts.push_back(e.track_a);
  return starts;
}

TEST(ContactStrain, EdgesAndTrianglesWithAnEndAtOrBesideTheGapAreLeftOut) {
  // A gap in either frame of the strain frame counts.
  for (const std::int32_t gap_frame : {0, 1}) {
    SCOPED_TRACE(gap_frame);
    const StrainMovie out = without_strain_near_gaps(movie_with_a_gap(gap_frame), 1);
    const StrainFrame& f = out.frames.front();
    // Columns 6, 7 and 8 are at or beside the gap: every edge touching them goes (5-6 .. 8-9).
    EXPECT_EQ(edge_starts(f), (std::vector<std::int32_t>{0, 1, 2, 3, 4}));
    // Triangles over columns c..c+2 survive only when none of them is 6, 7 or 8.
    ASSERT_EQ(f.triangles.size(), 4U);
    EXPECT_EQ(f.triangles.back().point_index[2], 5);
    // The points stay, so that the triangles' indices still mean the same points.
    EXPECT_EQ(f.points_from.size(), 10U);
    EXPECT_EQ(f.points_to.size(), 10U);
  }
}

Track track_at(std::int32_t id, std::int32_t first_frame, std::vector<double> x_px,
               std::vector<double> y_px) {
  Track t;
  t.id = id;
  t.first_frame = first_frame;
  t.x_px = std::move(x_px);
  t.y_px = std::move(y_px);
  return t;
}

std::vector<std::int32_t> ids_of(const std::vector<Track>& tracks) {
  std::vector<std::int32_t> ids;
  for (const Track& t : tracks) ids.push_back(t.id);
  return ids;
}

// The gap is cell (row 1, column 7) in camera frame 1: x 70-80, y 10-20.
TEST(ContactStrain, TracksThatStoodAtOrBesideTheGapInAnyFrameAreNotClear) {
  const ContactMap map = movie_with_a_gap(1).contact;
  const std::vector<Track> tracks = {
      track_at(0, 0, {75, 75}, {15, 15}),  // in the gap's cell in frame 1
      track_at(1, 0, {65, 65}, {25, 25}),  // in the cell diagonally beside it
      track_at(2, 0, {25, 25}, {15, 15}),  // far from it
      track_at(3, 0, {75}, {15}),          // there only in frame 0, in contact then
      track_at(4, 1, {5, 25}, {5, 35}),    // frame 1 far from it; frame 2 the map has not
  };
  EXPECT_EQ(ids_of(tracks_clear_of_gaps(tracks, map)), (std::vector<std::int32_t>{2, 3, 4}));
  EXPECT_EQ(ids_of(tracks_clear_of_gaps(tracks, map, 0)), (std::vector<std::int32_t>{1, 2, 3, 4}));
  // No map: nothing known to be out of contact.
  EXPECT_EQ(tracks_clear_of_gaps(tracks, ContactMap{}).size(), tracks.size());
}

TEST(ContactStrain, NoMarginLeavesOutOnlyTheGapsOwnCell) {
  const StrainMovie out = without_strain_near_gaps(movie_with_a_gap(0), 0);
  EXPECT_EQ(edge_starts(out.frames.front()), (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 8}));
}

TEST(ContactStrain, AMovieInFullContactOrWithoutAMapIsKeptWhole) {
  StrainMovie full = movie_with_a_gap(0);
  std::fill(full.contact.in_contact.begin(), full.contact.in_contact.end(), 1);
  EXPECT_EQ(without_strain_near_gaps(full).frames.front().edges.size(), 9U);
  StrainMovie unmeasured = movie_with_a_gap(0);
  unmeasured.contact = {};
  const StrainMovie kept = without_strain_near_gaps(unmeasured);
  EXPECT_EQ(kept.frames.front().edges.size(), 9U);
  EXPECT_EQ(kept.frames.front().triangles.size(), 8U);
}

// A live recording's map marks a frame it dropped as unseen, its cells 0: no claim of a gap.
TEST(ContactStrain, AFrameTheMapDidNotSeeLeavesNothingOut) {
  StrainMovie m = movie_with_a_gap(0);
  m.contact.frame_threshold = {5, 0};
  m.contact.frame_seen = {1, 0};
  std::fill(m.contact.in_contact.begin() + 40, m.contact.in_contact.end(), 0);
  std::fill(m.contact.ridge_contrast.begin() + 40, m.contact.ridge_contrast.end(), 0);
  EXPECT_EQ(edge_starts(without_strain_near_gaps(m, 0).frames.front()),
            (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 8}));
}

TEST(ContactStrain, APointJustOutsideTheImageBelongsToTheBorderCell) {
  StrainMovie m = movie_with_a_gap(0);
  // The gap moved to the last column; track 9 placed half a pixel beyond the right edge.
  m.contact.in_contact.assign(80, 1);
  m.contact.in_contact[1 * 10 + 9] = 0;
  m.frames.front().points_from[9].x_px = 100.5;
  const StrainMovie out = without_strain_near_gaps(m, 0);
  EXPECT_EQ(edge_starts(out.frames.front()), (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST(ContactStrain, StrainIsLeftOutOnlyWhereTheSkinSlides) {
  StrainMovie still = movie_with_a_gap(0);
  still.provenance.parameters_json = R"({"frames_in_view": 0})";
  EXPECT_FALSE(skin_slides_through_view(still));
  EXPECT_EQ(strain_in_contact(still).frames.front().edges.size(), 9U);
  StrainMovie sliding = movie_with_a_gap(0);
  sliding.provenance.parameters_json = R"({"frames_in_view": 12.5})";
  EXPECT_TRUE(skin_slides_through_view(sliding));
  EXPECT_EQ(edge_starts(strain_in_contact(sliding).frames.front()),
            (std::vector<std::int32_t>{0, 1, 2, 3, 4}));
}

// Eight camera frames, the points of row 1 in every one, and a strain frame between each two; the
// cell at column 7 is out of contact in camera frame 2 alone.
StrainMovie movie_with_a_moment_of_gap() {
  const StrainMovie one = movie_with_a_gap(0);
  StrainMovie m = one;
  m.camera_frame_count = 8;
  m.contact.in_contact.assign(8 * 40, 1);
  m.contact.ridge_contrast.assign(8 * 40, 20);
  m.contact.in_contact[2 * 40 + 17] = 0;
  m.contact.ridge_contrast[2 * 40 + 17] = 1;
  m.frames.clear();
  for (std::int32_t k = 0; k + 1 < 8; ++k) {
    StrainFrame f = one.frames.front();
    f.frame_from = k;
    f.frame_to = k + 1;
    for (auto& p : f.points_from) p.frame = k;
    for (auto& p : f.points_to) p.frame = k + 1;
    m.frames.push_back(f);
  }
  return m;
}

// A track smoothed over the frames on either side carries into them what its point at the rim
// measured: within the window, its strain is left out in the strain frames around that moment.
TEST(ContactStrain, ATracksStrainIsLeftOutAsFarAsItsSmoothingReaches) {
  const auto edges_per_frame = [](const StrainMovie& m) {
    std::vector<std::size_t> n;
    for (const auto& f : m.frames) n.push_back(f.edges.size());
    return n;
  };
  // The moment alone: the two strain frames that have camera frame 2 as an end.
  EXPECT_EQ(edges_per_frame(without_strain_near_gaps(movie_with_a_moment_of_gap(), 1, 0)),
            (std::vector<std::size_t>{9, 5, 5, 9, 9, 9, 9}));
  // Two frames either side: strain frames 0->1 to 4->5 reach camera frame 2.
  EXPECT_EQ(edges_per_frame(without_strain_near_gaps(movie_with_a_moment_of_gap(), 1, 2)),
            (std::vector<std::size_t>{5, 5, 5, 5, 5, 9, 9}));
  // strain_in_contact takes the window from the smoothing the capture used.
  StrainMovie sliding = movie_with_a_moment_of_gap();
  sliding.provenance.parameters_json =
      R"({"frames_in_view": 12.5, "smoothing_half_window_used": 2})";
  EXPECT_EQ(edges_per_frame(strain_in_contact(sliding)),
            (std::vector<std::size_t>{5, 5, 5, 5, 5, 9, 9}));
  sliding.provenance.parameters_json = R"({"frames_in_view": 12.5})";
  EXPECT_EQ(edges_per_frame(strain_in_contact(sliding)),
            (std::vector<std::size_t>{9, 5, 5, 9, 9, 9, 9}));
}

// Frame by frame (a causal tracker's step from one camera frame to the next): the same cells as
// the whole movie's rule with no smoothing window, from the two frames' maps alone.
TEST(ContactStrain, AStepIsJudgedByTheCellsOfItsTwoFramesAsTheMoviesRuleWould) {
  for (const std::int32_t gap_frame : {0, 1}) {
    SCOPED_TRACE(gap_frame);
    const StrainMovie whole = movie_with_a_gap(gap_frame);
    const ContactGrid& g = whole.contact.grid;
    const std::span<const std::uint8_t> all(whole.contact.in_contact);
    const auto near0 = cells_near_gap(g, all.subspan(0, 40));
    const auto near1 = cells_near_gap(g, all.subspan(40, 40));
    StrainFrame step = whole.frames.front();
    EXPECT_EQ(leave_out_strain_near_gaps(step, g, near0, near1), 4);
    const StrainFrame by_movie = without_strain_near_gaps(whole, 1, 0).frames.front();
    EXPECT_EQ(edge_starts(step), edge_starts(by_movie));
    EXPECT_EQ(step.triangles.size(), by_movie.triangles.size());
    EXPECT_EQ(step.points_from.size(), 10U);
  }
  // The cells marked: the gap's own and its eight neighbours, clipped by the grid.
  const StrainMovie m = movie_with_a_gap(0);
  const auto near = cells_near_gap(m.contact.grid, std::span(m.contact.in_contact).subspan(0, 40));
  EXPECT_EQ(std::count(near.begin(), near.end(), 1), 9);
  EXPECT_EQ(near[0 * 10 + 6], 1);
  EXPECT_EQ(near[2 * 10 + 8], 1);
  EXPECT_EQ(near[1 * 10 + 5], 0);
  // Maps of another size than the grid's are refused, not read past their end.
  StrainFrame step = m.frames.front();
  EXPECT_THROW(cells_near_gap(m.contact.grid, std::vector<std::uint8_t>(39, 1)),
               std::invalid_argument);
  EXPECT_THROW(leave_out_strain_near_gaps(step, m.contact.grid, near, std::vector<std::uint8_t>(3)),
               std::invalid_argument);
}

}  // namespace
}  // namespace tactile::capture
