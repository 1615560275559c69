// The viewer's strain panel made from a strain movie, and finding the strain movie a tactile
// movie was mapped from.

#include "tactile/mapping/strain_panel.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "../common/temp_dir.hpp"
#include "synthetic.hpp"
#include "tactile/capture/strain_movie_io.hpp"

namespace tactile::mapping {
namespace {

using ::testing::HasSubstr;

capture::TrackedPoint point(std::int32_t track, double x_mm, double y_mm) {
  capture::TrackedPoint p;
  p.track_id = track;
  p.x_mm = x_mm;
  p.y_mm = y_mm;
  return p;
}

// Two strain frames at 0.5 s and 0.6 s of a 3 x 2 mm field; a point of the second frame has
// drifted to x = -1 mm, outside the field.
capture::StrainMovie two_frames() {
  capture::StrainMovie m;
  m.field_width_mm = 3;
  m.field_height_mm = 2;
  capture::StrainFrame a;
  a.t_s = 0.5;
  a.points_to = {point(1, 0, 0), point(2, 1, 0), point(3, 0, 1)};
  a.edges = {{1, 2, 1, 1.01, 0.01}, {1, 3, 1, 0.98, -0.02}};
  capture::StrainFrame b = a;
  b.t_s = 0.6;
  b.points_to[0].x_mm = -1;
  b.edges[1].rel_change = std::numeric_limits<double>::quiet_NaN();
  m.frames = {a, b};
  return m;
}

TEST(StrainPanel, FramesStartAtTheFirstStrainFrameAndKeepEveryPointInView) {
  const movie::SideField f = strain_side_field(two_frames(), "strain: s.h5");
  EXPECT_EQ(f.title, "strain: s.h5");
  ASSERT_EQ(f.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(f.frames[0].t_s, 0.0);
  EXPECT_NEAR(f.frames[1].t_s, 0.1, 1e-12);
  // The drifted point sets the origin: everything moves 1 mm right, the field grows to 4 mm.
  EXPECT_DOUBLE_EQ(f.width_mm, 4.0);
  EXPECT_DOUBLE_EQ(f.height_mm, 2.0);
  ASSERT_EQ(f.frames[0].segments.size(), 2u);
  const auto& s = f.frames[0].segments[0];  // track 1 (0, 0) -> track 2 (1, 0)
  EXPECT_DOUBLE_EQ(s.x0_mm, 1.0);
  EXPECT_DOUBLE_EQ(s.x1_mm, 2.0);
  EXPECT_DOUBLE_EQ(s.y0_mm, 0.0);
  EXPECT_DOUBLE_EQ(s.value, 0.01);
  EXPECT_DOUBLE_EQ(f.frames[1].segments[0].x0_mm, 0.0);
  // A strain that could not be measured draws as none rather than poisoning the colours.
  EXPECT_DOUBLE_EQ(f.frames[1].segments[1].value, 0.0);
  EXPECT_GT(f.full_scale, 0.0);
  EXPECT_LE(f.full_scale, 0.02);
}

TEST(StrainPanel, RefusesMoviesItCannotDraw) {
  capture::StrainMovie m = two_frames();
  m.frames[1].edges.push_back({1, 9, 1, 1, 0.5});
  try {
    strain_side_field(m, "t");
    FAIL() << "an edge to a missing point was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("edge 1-9"));
  }
  EXPECT_THROW(strain_side_field(capture::StrainMovie{}, "t"), std::invalid_argument);
  m = two_frames();
  for (auto& frame : m.frames)
    for (auto& e : frame.edges) e.rel_change = 0;
  EXPECT_THROW(strain_side_field(m, "t"), std::invalid_argument);
}

TEST(StrainPanel, SourceStrainIsTheExplicitOneElseTheProvenancesIfItIsAStrainMovie) {
  const test::TempDir dir;
  auto strain = testing::make_movie(
      testing::GridSpec{.width_mm = 2, .height_mm = 2, .spacing_mm = 1},
      [](double, double, double) { return capture::PointMm{}; }, 2);
  testing::add_tracks(strain);
  capture::write_strain_movie(dir / "strain.h5", strain);
  std::ofstream(dir / "notes.h5") << "not HDF5";

  movie::TactileMovie movie;
  const auto movie_path = dir / "movie.h5";
  EXPECT_EQ(find_source_strain(movie, movie_path, "/any/explicit.h5"),
            std::filesystem::path("/any/explicit.h5"));
  EXPECT_EQ(find_source_strain(movie, movie_path, {}), std::nullopt);  // no provenance
  movie.provenance.input = (dir / "strain.h5").string();
  EXPECT_EQ(find_source_strain(movie, movie_path, {}), dir / "strain.h5");
  // Recorded where it was made, since moved beside the movie.
  movie.provenance.input = "/elsewhere/strain.h5";
  EXPECT_EQ(find_source_strain(movie, movie_path, {}), dir / "strain.h5");
  movie.provenance.input = (dir / "notes.h5").string();
  EXPECT_EQ(find_source_strain(movie, movie_path, {}), std::nullopt);
  movie.provenance.input = "synthetic bump scene";
  EXPECT_EQ(find_source_strain(movie, movie_path, {}), std::nullopt);
}

}  // namespace
}  // namespace tactile::mapping
