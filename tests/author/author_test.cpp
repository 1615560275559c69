// The authoring window's model without a window: a mapping with its figures, the background
// mapper (newest request wins) and A/B saved as an experiment that the experiment library reads
// back to the same mappings.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "tactile/author/outcome.hpp"
#include "tactile/author/remapper.hpp"
#include "tactile/author/save.hpp"
#include "tactile/capture/ground_truth.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::author {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<const capture::StrainMovie> bump_strain(int frames = 40) {
  capture::SceneSpec spec;
  spec.frame_count = frames;
  return std::make_shared<const capture::StrainMovie>(
      capture::ground_truth_strain_movie(spec, 0.5));
}

TEST(AuthorOutcome, IsTheMappingLibrarysMovieWithItsFigures) {
  const auto strain = bump_strain();
  mapping::MapRequest request;
  request.params.gain_um_per_strain = 2000;
  const MappingOutcome o = map_for_authoring(*strain, request);
  ASSERT_TRUE(o.error.empty()) << o.error;
  mapping::MappingParams params = request.params;
  const movie::TactileMovie direct =
      mapping::map_strain_movie(*strain, movie::resolve_layout("stress"), params);
  EXPECT_EQ(o.movie.deflection_um, direct.deflection_um);
  // The integrated method reproduces the ground truth's strain (correlation 1 by design).
  EXPECT_GT(o.metrics.strain_correlation, 0.99);
  ASSERT_FALSE(o.over_time.empty());
  EXPECT_LE(o.over_time.size(), static_cast<std::size_t>(kFidelityStretches));
  for (std::size_t k = 1; k < o.over_time.size(); ++k)
    EXPECT_GT(o.over_time[k].t0_s, o.over_time[k - 1].t0_s);
  EXPECT_EQ(o.saturated_share.size(), static_cast<std::size_t>(o.layout.contactor_count()));
}

TEST(AuthorOutcome, SaturationIsShownWhereTheMovieClamps) {
  const auto strain = bump_strain();
  mapping::MapRequest request;
  request.params.gain_um_per_strain = 1e6;  // far beyond the layout's range
  const MappingOutcome o = map_for_authoring(*strain, request);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_GT(o.metrics.saturated_fraction, 0.0);
  float most = 0;
  for (float s : o.saturated_share) most = std::max(most, s);
  EXPECT_GT(most, 0.0f);
}

TEST(AuthorOutcome, ARefusedRequestIsAnOutcomeThatSaysWhy) {
  const auto strain = bump_strain();
  mapping::MapRequest request;
  request.layout = "hexagonal";
  const MappingOutcome o = map_for_authoring(*strain, request);
  EXPECT_NE(o.error.find("hexagonal"), std::string::npos) << o.error;
  EXPECT_EQ(o.movie.frame_count, 0);
}

TEST(Remapper, TheNewestRequestWinsAndTheOthersAreSkipped) {
  Remapper remapper(bump_strain(120));
  mapping::MapRequest request;
  std::uint64_t last = 0;
  for (int i = 1; i <= 20; ++i) {
    request.params.gain_um_per_strain = 100.0 * i;
    last = remapper.submit(request);
  }
  const Remapper::Done done = remapper.wait_for(last);
  ASSERT_TRUE(done.outcome);
  EXPECT_EQ(done.number, last);
  EXPECT_DOUBLE_EQ(done.outcome->request.params.gain_um_per_strain, 2000.0);
  // Twenty requests submitted faster than one mapping: most were never mapped.
  EXPECT_LT(remapper.mapped_count(), 20u);
  EXPECT_EQ(remapper.mapped_count() + remapper.skipped_count(), 20u);
  EXPECT_FALSE(remapper.busy());
}

TEST(AuthorSave, TheExperimentHoldsAAndBAndReopensToThem) {
  const fs::path dir = fs::path(::testing::TempDir()) / "author-save";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto strain = bump_strain();
  capture::write_strain_movie(dir / "strain.h5", *strain);
  mapping::MapRequest a;
  a.strain = dir / "strain.h5";
  mapping::MapRequest b = a;
  b.params.method = mapping::MappingMethod::proportional;
  b.params.gain_um_per_strain = 3000;
  const MappingOutcome oa = map_for_authoring(*strain, a);
  const MappingOutcome ob = map_for_authoring(*strain, b);
  const Saved saved = save_authoring(dir / "out", "ab", dir / "strain.h5", &oa, ob);
  ASSERT_EQ(saved.movies.size(), 2u);
  // Each saved movie holds the outcome's deflections as they were shown.
  EXPECT_EQ(movie::read_tactile_movie(saved.movies[0]).deflection_um, oa.movie.deflection_um);
  EXPECT_EQ(movie::read_tactile_movie(saved.movies[1]).deflection_um, ob.movie.deflection_um);
  EXPECT_TRUE(fs::exists(saved.hjif));
  EXPECT_TRUE(fs::exists(saved.wav));
  // Two methods x two gains: a grid of four runs, A first and B last.
  const experiments::Experiment ex = experiments::read_experiment(saved.experiment);
  EXPECT_EQ(ex.runs.size(), 4u);
  const ExperimentChoices back = choices_of(ex);
  ASSERT_TRUE(back.a);
  EXPECT_EQ(back.a->params.method, mapping::MappingMethod::integrated);
  EXPECT_DOUBLE_EQ(back.a->params.gain_um_per_strain, 1000);
  EXPECT_EQ(back.current.params.method, mapping::MappingMethod::proportional);
  EXPECT_DOUBLE_EQ(back.current.params.gain_um_per_strain, 3000);
  EXPECT_TRUE(fs::equivalent(back.strain_file, dir / "strain.h5"));
  EXPECT_EQ(describe_change(a, b), "--method integrated -> proportional, --gain 1000 -> 3000");
}

// A layout file typed in the window could be where Save writes its experiment: refused, the
// layout file left as it was.
TEST(AuthorSave, NeverWritesOverALayoutFileTheMappingRead) {
  const fs::path dir = fs::path(::testing::TempDir()) / "author-over-layout";
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  const std::string layout_text = movie::layout_to_json(movie::resolve_layout("stress"));
  write_text_atomically(dir / "out" / "ab.json", layout_text);
  const auto strain = bump_strain();
  capture::write_strain_movie(dir / "strain.h5", *strain);
  mapping::MapRequest request;
  request.layout = (dir / "out" / "ab.json").string();
  const MappingOutcome o = map_for_authoring(*strain, request);
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_THROW(save_authoring(dir / "out", "ab", dir / "strain.h5", nullptr, o),
               OutputIsInputError);
  std::ifstream in(dir / "out" / "ab.json");
  const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(after, layout_text);
  EXPECT_FALSE(fs::exists(dir / "out" / "movies"));
}

TEST(AuthorSave, RefusesAFailedMappingAndABadName) {
  const auto strain = bump_strain();
  mapping::MapRequest bad;
  bad.layout = "nowhere.json";
  const MappingOutcome failed = map_for_authoring(*strain, bad);
  const fs::path dir = fs::path(::testing::TempDir()) / "author-refuse";
  EXPECT_THROW(save_authoring(dir, "x", "strain.h5", nullptr, failed), std::invalid_argument);
  EXPECT_THROW(experiment_json("../up", "strain.h5", {mapping::MapRequest{}}),
               std::invalid_argument);
  EXPECT_THROW(experiment_json("x", "strain.h5", {}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace tactile::author
