// Every file a command writes says where it came from in the same words: the input it was made
// from (a path as given, or none), the program's version, the command line as typed, the method
// and its parameters, and the time.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/version.hpp"
#include "tactile/movie/movie_io.hpp"

namespace {

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(ProvenanceCli, SynthCaptureAndMapEachRecordInputCommandMethodAndParameters) {
  const tactile::test::TempDir dir;
  const std::string seq = (dir.path() / "seq").string();
  const std::string synth = "synth " + seq + " --scene flat-slide --frames 40 --seed 5";
  auto r = run_tactile(synth);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json scene;
  std::ifstream(dir.path() / "seq" / "scene.json") >> scene;
  const auto& made = scene.at("provenance");
  EXPECT_EQ(made.at("input"), "");  // rendered, from no file
  EXPECT_EQ(made.at("method"), "synthetic scene");
  EXPECT_THAT(made.at("command_line").get<std::string>(), HasSubstr(synth));
  EXPECT_EQ(made.at("program_version"), tactile::kVersion);
  EXPECT_THAT(made.at("created_utc").get<std::string>(), StartsWith("20"));
  const auto spec = nlohmann::json::parse(made.at("parameters_json").get<std::string>());
  EXPECT_EQ(spec.at("scene"), "flat-slide");
  EXPECT_EQ(spec.at("frame_count"), 40);
  EXPECT_EQ(spec.at("seed"), 5);

  const std::string strain_file = (dir.path() / "strain.h5").string();
  const std::string capture =
      "capture " + seq + " --px-per-mm 62 --min-track 10 --out " + strain_file;
  r = run_tactile(capture);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto strain = tactile::capture::read_strain_movie(strain_file);
  EXPECT_EQ(strain.provenance.input, seq);
  EXPECT_EQ(strain.provenance.method, "capture");
  EXPECT_THAT(strain.provenance.command_line, HasSubstr(capture));
  EXPECT_EQ(strain.provenance.program_version, tactile::kVersion);
  const auto settings = nlohmann::json::parse(strain.provenance.parameters_json);
  EXPECT_EQ(settings.at("frame_rate_hz"), 60.0);
  EXPECT_EQ(settings.at("span_frames"), 1);
  EXPECT_EQ(settings.at("min_track_frames"), 10);
  EXPECT_NEAR(settings.at("mm_per_px").get<double>(), 1.0 / 62, 1e-12);

  const std::string movie_file = (dir.path() / "movie.h5").string();
  const std::string map = "map " + strain_file + " --method proportional --out " + movie_file;
  r = run_tactile(map);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto movie = tactile::movie::read_tactile_movie(movie_file);
  EXPECT_EQ(movie.provenance.input, strain_file);
  EXPECT_EQ(movie.provenance.method, "proportional");
  EXPECT_THAT(movie.provenance.command_line, HasSubstr(map));
  EXPECT_EQ(movie.provenance.program_version, tactile::kVersion);
  EXPECT_THAT(movie.provenance.parameters_json, HasSubstr("\"method\":\"proportional\""));
  EXPECT_THAT(movie.provenance.created_utc, StartsWith("20"));
}

}  // namespace
