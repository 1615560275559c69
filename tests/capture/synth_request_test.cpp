// The synth request's rules, which the command line and the Python module both apply: a scene's
// options are not a print's, a print's need one, a speed or a distance (not both), and every
// option left unset takes the spec's own default.

#include "tactile/capture/synth_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"

namespace {

using tactile::OptionSpelling;
using tactile::RequestError;
using tactile::capture::SynthRequest;
using tactile::test::error_of;
using ::testing::HasSubstr;

const std::filesystem::path kPrint =
    std::filesystem::path(TACTILE_TEST_DATA_DIR) / "polyu-hrf-pores" / "image_12.jpg";

SynthRequest print_request() {
  SynthRequest r;
  r.out_dir = "never";
  r.from_print = kPrint;
  return r;
}

TEST(SynthRequest, UnsetOptionsTakeTheSpecsDefaults) {
  SynthRequest r;
  r.out_dir = "never";
  const auto scene = tactile::capture::resolve(r, OptionSpelling::cli);
  ASSERT_TRUE(scene.scene && !scene.warp);
  const tactile::capture::SceneSpec d;
  EXPECT_EQ(scene.scene->frame_count, d.frame_count);
  EXPECT_EQ(scene.scene->speed_mm_per_s, d.speed_mm_per_s);
  EXPECT_EQ(scene.scene->seed, d.seed);
  const auto print = tactile::capture::resolve(print_request(), OptionSpelling::cli);
  ASSERT_TRUE(print.warp && !print.scene);
  const tactile::capture::PrintWarpSpec w;
  // The two kinds of sequence keep their own lengths: 30 frames of a print, not a scene's 180.
  EXPECT_EQ(print.warp->frame_count, w.frame_count);
  EXPECT_NE(w.frame_count, d.frame_count);
  EXPECT_EQ(print.warp->strain, w.strain);
  EXPECT_EQ(print.warp->slide_x_mm, w.slide_x_mm);
  // The marks beside a PolyU print are found.
  ASSERT_TRUE(print.marks.has_value());
  EXPECT_EQ(print.marks->filename(), "pores_12.txt");
}

TEST(SynthRequest, OptionsGivenReachTheSpec) {
  SynthRequest r = print_request();
  r.scene.frames = 12;
  r.scene.seed = std::numeric_limits<std::uint64_t>::max();
  r.print.strain_pct = 2.5;
  r.print.exposure_ms = 4;
  r.print.rate_hz = 120;
  r.print.slide_speed_mm_per_s = 3;
  const auto w = *tactile::capture::resolve(r, OptionSpelling::cli).warp;
  EXPECT_EQ(w.frame_count, 12);
  EXPECT_EQ(w.seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_DOUBLE_EQ(w.strain, 0.025);
  EXPECT_DOUBLE_EQ(w.exposure_s, 0.004);
  // 12 frames at 120 Hz last 11 / 120 s: a slide at 3 mm/s covers 0.275 mm.
  EXPECT_NEAR(w.slide_x_mm, 3.0 * 11 / 120, 1e-12);
}

TEST(SynthRequest, AScenesOptionIsNotAPrintsAndAPrintsNeedsOne) {
  SynthRequest r = print_request();
  r.scene.speed_mm_per_s = 3;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(r, OptionSpelling::cli); }),
              HasSubstr("--speed: describes a synthetic scene, not --from-print"));
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(r, OptionSpelling::python); }),
              HasSubstr("speed: describes a synthetic scene, not from_print"));
  SynthRequest s;
  s.out_dir = "never";
  s.print.warp = tactile::capture::WarpPattern::bump;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(s, OptionSpelling::cli); }),
              HasSubstr("--warp: needs --from-print"));
  s = SynthRequest{};
  s.out_dir = "never";
  s.marks = kPrint;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(s, OptionSpelling::cli); }),
              HasSubstr("--marks: needs --from-print"));
}

TEST(SynthRequest, ASpeedOrADistanceNotBoth) {
  SynthRequest r = print_request();
  r.print.turn_rate_deg_per_s = 10;
  r.print.turn_deg = 1;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(r, OptionSpelling::cli); }),
              HasSubstr("--turn-rate: not with --turn"));
}

TEST(SynthRequest, FullSlipNeedsATravelSpeed) {
  SynthRequest r = print_request();
  r.print.warp = tactile::capture::WarpPattern::full_slip;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(r, OptionSpelling::cli); }),
              HasSubstr("--warp full-slip: needs --travel-speed above 0"));
  r.print.travel_speed_mm_per_s = 10;
  EXPECT_NO_THROW(tactile::capture::resolve(r, OptionSpelling::cli));
}

TEST(SynthRequest, ValuesOutOfRangeAreRefusedByTheirRow) {
  SynthRequest r = print_request();
  r.print.strain_pct = 50;
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(r, OptionSpelling::cli); }),
              HasSubstr("--strain-pct: 50 is out of range: must be from -20 to 20"));
  SynthRequest s;
  s.out_dir = "";
  EXPECT_THAT(error_of<RequestError>([&] { tactile::capture::resolve(s, OptionSpelling::python); }),
              HasSubstr("out_dir: the path is empty"));
}

// A seed is taken whole, as digits: neither wrapped (-1) nor rounded (beyond 2^53).
TEST(SynthRequest, ASeedKeepsEveryDigit) {
  const auto* row = tactile::find_option(tactile::capture::synth_options(), "seed");
  ASSERT_NE(row, nullptr);
  SynthRequest r;
  tactile::set_option(r, *row, std::uint64_t{18446744073709551615ULL}, OptionSpelling::cli);
  EXPECT_EQ(r.scene.seed, 18446744073709551615ULL);
  tactile::set_option(r, *row, std::int64_t{9007199254740993}, OptionSpelling::cli);
  EXPECT_EQ(r.scene.seed, 9007199254740993ULL);
  EXPECT_THAT(error_of<RequestError>(
                  [&] { tactile::set_option(r, *row, std::int64_t{-1}, OptionSpelling::python); }),
              HasSubstr("seed: -1 is not a whole number from 0 to 2^64 - 1"));
  EXPECT_THAT(error_of<RequestError>(
                  [&] { tactile::set_option(r, *row, std::string("1e3"), OptionSpelling::cli); }),
              HasSubstr("--seed: 1e3 is not a whole number"));
}

TEST(SynthRequest, StaleFramesInTheOutputAreRefusedBeforeAnyWork) {
  const tactile::test::TempDir dir("synth_stale");
  SynthRequest r;
  r.out_dir = dir.path() / "seq";
  r.scene.frames = 3;
  tactile::capture::run_synth(tactile::capture::resolve(r, OptionSpelling::cli), "");
  EXPECT_TRUE(std::filesystem::exists(r.out_dir / "frame_002.png"));
  r.scene.frames = 2;
  EXPECT_THAT(error_of([&] {
                tactile::capture::run_synth(tactile::capture::resolve(r, OptionSpelling::cli), "");
              }),
              HasSubstr("OUT_DIR " + r.out_dir.string() + " already holds 1 image file(s)"));
}

// A marks file that is not one names the option that gave it, then the file and its line.
TEST(SynthRequest, BadMarksAreNamedByTheirOption) {
  const tactile::test::TempDir dir("synth_marks");
  const auto marks = dir.path() / "marks.txt";
  std::ofstream(marks) << "12 34\nnot a mark\n";
  SynthRequest r = print_request();
  r.out_dir = dir.path() / "seq";
  r.marks = marks;
  r.scene.frames = 2;
  EXPECT_THAT(error_of([&] {
                tactile::capture::run_synth(tactile::capture::resolve(r, OptionSpelling::cli), "");
              }),
              HasSubstr("--marks: " + marks.string() + ":2:"));
  EXPECT_FALSE(std::filesystem::exists(r.out_dir / "frame_000.png"));
}

}  // namespace
