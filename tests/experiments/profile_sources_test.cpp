// An experiment refuses method "profile" on a file source: the method renders a scene's surface,
// which a recorded strain movie does not have.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "../common/temp_dir.hpp"
#include "synthetic.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::experiments {
namespace {

using ::testing::HasSubstr;
namespace testing = tactile::mapping::testing;

TEST(Profile, ExperimentsRefuseItOnFileSources) {
  const tactile::test::TempDir dir_tmp;
  const std::filesystem::path& dir = dir_tmp.path();
  auto movie = testing::make_movie(
      testing::GridSpec{.width_mm = 4, .height_mm = 4, .spacing_mm = 1},
      [](double, double, double) {
        return capture::PointMm{0, 0};
      },
      5, 60.0);
  testing::add_tracks(movie);
  // A camera of 50 px/mm that sees exactly the grid, as the strain movie's reader requires.
  movie.calibration.mm_per_px = 0.02;
  movie.calibration.px_to_mm = {0.02, 0, 0, 0, 0.02, 0, 0, 0, 1};
  movie.calibration.image_width_px = 200;
  movie.calibration.image_height_px = 200;
  capture::write_strain_movie(dir / "rec.h5", movie);
  try {
    parse_experiment(R"({"name": "p", "seed": 1, "sources": [{"name": "rec", "file": "rec.h5"}],
                         "layouts": ["stress"], "methods": ["profile"]})",
                     "p.json", dir);
    FAIL() << "accepted";
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("method 'profile' needs a scene, but source 'rec' is a file"));
  }
}

}  // namespace
}  // namespace tactile::experiments
