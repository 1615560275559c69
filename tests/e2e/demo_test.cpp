// The main job, end to end: `tactile demo --headless` on the built-in scene, then its files are
// read back and checked against what the scene implies.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/movie/movie_io.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

// The fixture e2e.demo (tests/CMakeLists.txt) ran `tactile demo --headless --keep --out DIR`
// and saved what it printed to DIR.log.
class DemoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ifstream log(out_.string() + ".log");
    ASSERT_TRUE(log) << "the e2e.demo fixture did not run (ctest runs it first)";
    std::stringstream s;
    s << log.rdbuf();
    output_ = s.str();
  }
  const fs::path out_ = TACTILE_E2E_DEMO_DIR;
  std::string output_;
};

// Root-mean-square deflection of each frame.
std::vector<double> activity(const tactile::movie::TactileMovie& m) {
  std::vector<double> a(static_cast<std::size_t>(m.frame_count));
  for (std::int32_t f = 0; f < m.frame_count; ++f) {
    double s = 0;
    for (float d : m.frame(f)) s += static_cast<double>(d) * d;
    a[static_cast<std::size_t>(f)] = std::sqrt(s / m.layout.contactor_count());
  }
  return a;
}

double mean(const std::vector<double>& v, std::size_t from, std::size_t to) {
  return std::accumulate(v.begin() + static_cast<std::ptrdiff_t>(from),
                         v.begin() + static_cast<std::ptrdiff_t>(to), 0.0) /
         static_cast<double>(to - from);
}

}  // namespace

TEST_F(DemoTest, RunsHeadlessAndSaysWhatItDid) {
  EXPECT_THAT(output_, HasSubstr("headless"));
  EXPECT_THAT(output_, HasSubstr("preview"));
}

TEST_F(DemoTest, WritesEveryFileAskedFor) {
  for (const char* f :
       {"strain.h5", "movie.h5", "preview.png", "calibration.json", "frames/frame_000.png",
        "frames/calibration/dot_grid.png", "csv/tracks.csv", "csv/edges.csv", "csv/movie.csv"}) {
    EXPECT_TRUE(fs::exists(out_ / f)) << f;
  }
  const tactile::capture::GrayImage preview = tactile::capture::read_image(out_ / "preview.png");
  EXPECT_GT(preview.width_px, 200);
  EXPECT_GT(preview.height_px, 100);
}

TEST_F(DemoTest, StrainMovieCoversTheScene) {
  const auto strain = tactile::capture::read_strain_movie(out_ / "strain.h5");
  EXPECT_DOUBLE_EQ(strain.frame_rate_hz, 60.0);
  // Measured from frames rendered in memory: no input file; the scene is with the parameters.
  EXPECT_EQ(strain.provenance.input, "");
  EXPECT_EQ(strain.provenance.method, "capture");
  EXPECT_THAT(strain.provenance.parameters_json, HasSubstr("\"scene\":\"bump\""));
  EXPECT_THAT(strain.provenance.command_line, HasSubstr(" demo "));
  // 180 camera frames at span 1 give at most 179 frame pairs.
  EXPECT_GE(strain.frames.size(), 150u);
  EXPECT_LE(strain.frames.size(), 179u);
  std::size_t edges = 0;
  for (const auto& f : strain.frames) edges += f.edges.size();
  EXPECT_GT(edges / strain.frames.size(), 100u) << "too few tracked edges per frame";
}

TEST_F(DemoTest, MovieHasTheStressShapeRateAndDuration) {
  const auto movie = tactile::movie::read_tactile_movie(out_ / "movie.h5");
  EXPECT_EQ(movie.layout.name, "stress");
  EXPECT_EQ(movie.layout.rows, 10);
  EXPECT_EQ(movie.layout.cols, 10);
  EXPECT_DOUBLE_EQ(movie.rate_hz, 700.0);
  // 180 frames at 60 Hz span 3 s; the strain exists between the first and last frame pair.
  EXPECT_GT(movie.duration_s(), 2.5);
  EXPECT_LE(movie.duration_s(), 3.01);
  EXPECT_EQ(movie.deflection_um.size(), static_cast<std::size_t>(movie.frame_count) * 100u);
  EXPECT_THAT(movie.provenance.method, ::testing::Not(::testing::IsEmpty()));
  EXPECT_EQ(movie.provenance.input, (out_ / "strain.h5").string());
  EXPECT_THAT(movie.provenance.command_line, HasSubstr(" demo "));
}

TEST_F(DemoTest, ActivityRisesAndFallsAsTheBumpPasses) {
  const auto movie = tactile::movie::read_tactile_movie(out_ / "movie.h5");
  const std::vector<double> a = activity(movie);
  const std::size_t n = a.size();
  ASSERT_GT(n, 100u);
  const std::size_t tenth = n / 10;
  const double start = mean(a, 0, tenth);
  const double end = mean(a, n - tenth, n);
  // Peak of the activity smoothed over a tenth of the movie.
  double peak = 0;
  std::size_t peak_at = 0;
  for (std::size_t i = 0; i + tenth <= n; ++i) {
    const double m = mean(a, i, i + tenth);
    if (m > peak) {
      peak = m;
      peak_at = i + tenth / 2;
    }
  }
  // The scene's finger path is centred on the bump and the bump's push on the skin follows the
  // contact pressure, sqrt(1 - r^2) over the contact ellipse (docs/capture-models.md): with the
  // bump 3.6 mm from the patch centre at either end of the slide (semi-axis 4.8 mm) its effect
  // there is sqrt(1 - 0.75^2) = 0.66 of the effect at the middle. Measured activity must show
  // that hump: peak in the middle part of the movie, both ends clearly lower.
  EXPECT_GT(peak, 1.0) << "the bump should move contactors by more than a micrometre";
  EXPECT_GT(peak_at, n / 5);
  EXPECT_LT(peak_at, n - n / 5);
  EXPECT_LT(start, 0.8 * peak);
  EXPECT_LT(end, 0.8 * peak);
}
