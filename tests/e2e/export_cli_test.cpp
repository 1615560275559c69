// `tactile export` and `tactile import` on the demo's movie: HJIF and WAV written, the HJIF read
// back into the same movie, usage errors exit 2 and bad files exit 1 naming the field.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/movie/movie_io.hpp"

using tactile::test::demo_dir;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

TEST(ExportCli, HjifRoundTripKeepsTheDemoMovie) {
  tactile::test::TempDir dir;
  const std::string movie = (demo_dir() / "movie.h5").string();
  const std::string hjif = (dir / "m.hjif").string(), wav = (dir / "m.wav").string();
  auto r = run_tactile("export " + movie + " --hjif " + hjif + " --wav " + wav);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("export: 100 channels, level 1, timescale 700"));
  EXPECT_THAT(r.output, HasSubstr("1.0 = 50 um"));
  EXPECT_GT(std::filesystem::file_size(wav), 100U * 4);
  const std::string back = (dir / "back.h5").string();
  r = run_tactile("import " + hjif + " --out " + back);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("import: 10 x 10 contactors (stress)"));
  const auto a = tactile::movie::read_tactile_movie(movie);
  const auto b = tactile::movie::read_tactile_movie(back);
  ASSERT_EQ(a.frame_count, b.frame_count);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.layout.name, b.layout.name);
  EXPECT_EQ(a.provenance.input, b.provenance.input);
  EXPECT_EQ(a.provenance.parameters_json, b.provenance.parameters_json);
  double worst = 0;
  for (std::size_t i = 0; i < a.deflection_um.size(); ++i) {
    worst = std::max(worst, std::abs(double(a.deflection_um[i]) - b.deflection_um[i]));
  }
  EXPECT_LT(worst, 0.1);

  r = run_tactile("import " + hjif + " --out " + back + " --layout stress2");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is 8 x 8 (rows x cols) but the channels' actuator_resolution "
                                  "is 10 x 10"));
}

TEST(ExportCli, UsageErrorsAndBadFiles) {
  tactile::test::TempDir dir;
  const std::string movie = (demo_dir() / "movie.h5").string();
  auto r = run_tactile("export " + movie);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("give --hjif OUT.hjif, --wav OUT.wav or both"));
  r = run_tactile("export " + movie + " --hjif " + movie);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // Found by the third hostile-input run: the names swapped wrote a WAV called x.hjif and an
  // HJIF called x.wav, files no other tool opens. Refused before any work.
  for (const std::string& args :
       {" --hjif " + (dir / "x.wav").string(), " --wav " + (dir / "x.hjif").string(),
        " --hjif " + (dir / "ok.hjif").string() + " --wav " + (dir / "x.mp3").string()}) {
    r = run_tactile("export " + movie + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_THAT(r.output, ::testing::ContainsRegex("--(hjif|wav) [^ ]+: the name must end in "
                                                   "\\.(hjif|wav)"))
        << r.output;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << args;
  }
  const auto bad = dir / "bad.hjif";
  std::ofstream(bad) << R"({"version": "2023"})";
  r = run_tactile("import " + bad.string() + " --out " + (dir / "x.h5").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr(bad.string() + ": missing field 'date'"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
}

}  // namespace
