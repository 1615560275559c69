// The export request, which `tactile export` and Python's export() both run: at least one
// output, each with its own extension, never over the input, all written or none.

#include "tactile/movie/export_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/movie/hjif.hpp"
#include "test_movies.hpp"

namespace {

using tactile::OptionSpelling;
using tactile::RequestError;
using tactile::movie::ExportRequest;
using tactile::test::error_of;
using ::testing::HasSubstr;

const tactile::movie::TactileMovie kMovie =
    tactile::movie::testing::sine_movie(tactile::movie::stress_layout(), 700, 70, 50);

TEST(ExportRequest, NeedsAnOutputInTheFrontEndsSpelling) {
  const ExportRequest r;
  EXPECT_THAT(
      error_of<RequestError>([&] { tactile::movie::run_export(r, kMovie, OptionSpelling::cli); }),
      HasSubstr("give --hjif OUT.hjif, --wav OUT.wav or both"));
  EXPECT_THAT(error_of<RequestError>(
                  [&] { tactile::movie::run_export(r, kMovie, OptionSpelling::python); }),
              HasSubstr("give hjif OUT.hjif, wav OUT.wav or both"));
}

TEST(ExportRequest, TicksPerSampleWithinTheProfilesTimescale) {
  ExportRequest r;
  r.hjif = "x.hjif";
  r.ticks_per_sample = 0;
  EXPECT_THAT(
      error_of<RequestError>([&] { tactile::movie::check_request(r, OptionSpelling::cli); }),
      HasSubstr("--ticks-per-sample: 0 is out of range: must be from 1 to 48000"));
}

TEST(ExportRequest, WritesBothFilesWithTheTicksAsked) {
  const tactile::test::TempDir dir("export_request");
  ExportRequest r;
  r.hjif = dir.path() / "m.hjif";
  r.wav = dir.path() / "m.wav";
  r.ticks_per_sample = 4;
  const auto s = tactile::movie::run_export(r, kMovie, OptionSpelling::cli);
  ASSERT_TRUE(s.hjif && s.wav_full_scale_um);
  // timescale = rate x ticks per sample.
  EXPECT_EQ(s.hjif->timescale, 700 * 4);
  EXPECT_EQ(s.hjif->channels, 100);
  EXPECT_EQ(s.lines.size(), 2u);
  EXPECT_EQ(tactile::movie::read_hjif(*r.hjif).frame_count, kMovie.frame_count);
  EXPECT_GT(std::filesystem::file_size(*r.wav), 44u);
}

TEST(ExportRequest, AWrongExtensionOrTheInputItselfIsRefusedAndNothingWritten) {
  const tactile::test::TempDir dir("export_refused");
  ExportRequest r;
  r.hjif = dir.path() / "m.hjif";
  r.wav = dir.path() / "m.hjif.txt";
  EXPECT_THAT(error_of([&] { tactile::movie::run_export(r, kMovie, OptionSpelling::cli); }),
              HasSubstr("--wav"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  ExportRequest over;
  over.movie = dir.path() / "m.wav";
  over.wav = over.movie;
  EXPECT_THAT(error_of([&] { tactile::movie::check_outputs(over, OptionSpelling::cli); }),
              HasSubstr("MOVIE_H5"));
}

}  // namespace
