// Numeric options out of range say so with the bounds a person would write, never the
// 300-digit limits of a double.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

// GCC 12 with -O2 and the sanitizers warns falsely (-Wmaybe-uninitialized) inside <regex>'s
// own automaton; the warning is attributed to the header's lines, so it is silenced there only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop
#include <string>

#include "run.hpp"
#include "tactile/movie/movie_io.hpp"

using tactile::test::demo_dir;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

// Exit 2 with `message` and no number of 20 digits or more.
void expect_readable_range_error(const std::string& args, const std::string& message) {
  const auto r = run_tactile(args);
  EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
  EXPECT_THAT(r.output, HasSubstr(message)) << args;
  EXPECT_FALSE(std::regex_search(r.output, std::regex("[0-9]{20}"))) << args << ": " << r.output;
}

TEST(RangeErrors, ReadLikeAPersonWroteThem) {
  const std::string image = (tactile::test::test_data("polyu-hrf-pores") / "image_01.jpg").string();
  expect_readable_range_error("features " + image + " --px-per-mm 0",
                              "--px-per-mm: 0 is out of range: must be from 2 to 5000");
  expect_readable_range_error(
      "map " + (demo_dir() / "strain.h5").string() + " --out x.h5 --rate-hz -5",
      "--rate-hz: -5 is out of range: must be a whole number of hertz from 1 to 65535");
  // Refused when the movie is made, not later by `play`: no device plays half hertz.
  expect_readable_range_error(
      "map " + (demo_dir() / "strain.h5").string() + " --out x.h5 --rate-hz 500.5",
      "--rate-hz: 500.5 is out of range: must be a whole number of hertz from 1 to 65535");
  expect_readable_range_error("train-pores --prints " +
                                  tactile::test::test_data("polyu-hrf-pores").string() +
                                  " --px-per-mm 47 --out x.json --l2 -1",
                              "--l2: -1 is out of range: must be from 0 to 1000000");
  expect_readable_range_error("view " + (demo_dir() / "movie.h5").string() + " --at -0.5",
                              "--at: -0.5 is out of range: must be >= 0");
  expect_readable_range_error("synth x --speed 1000",
                              "--speed: 1000 is out of range: must be from "
                              "0 to 100");
  expect_readable_range_error(
      "capture " + demo_dir().string() + " --px-per-mm 62 --out x.h5 --span 0",
      "--span: 0 is out of range: must be from 1 to 10000");
  expect_readable_range_error("bench stream --seconds 0.01",
                              "--seconds: 0.01 is out of range: must be from 0.1 to 600");
  expect_readable_range_error("synth x --frames 2.5", "--frames: 2.5 is not a whole number");
  expect_readable_range_error(
      "live " + demo_dir().string() + " --px-per-mm 62 --headless --neighbour-sigma 7",
      "--neighbour-sigma: 7 is out of range: must be from 0 to 5");
  const std::string prints = tactile::test::test_data("polyu-hrf-pores").string();
  expect_readable_range_error("bench live " + prints + " --seconds 0.1",
                              "--seconds: 0.1 is out of range: must be from 0.5 to 600");
  expect_readable_range_error("bench live " + prints + " --travel 1e308",
                              "--travel: 1e308 is out of range: must be from 1 to 500");
}

TEST(RangeErrors, BenchLiveNamesAPrintItDoesNotHave) {
  const std::string prints = tactile::test::test_data("polyu-hrf-pores").string();
  const auto r = run_tactile("bench live " + prints + " --print 99 --out bench-live-none");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--print 99: " + prints + " holds no print image_99"));
}

TEST(RangeErrors, BenchLiveSaysHowACaseIsWritten) {
  const std::string prints = tactile::test::test_data("polyu-hrf-pores").string();
  const auto form = run_tactile("bench live " + prints + " --case 640x484 --out bench-live-none");
  EXPECT_EQ(form.exit_code, 2) << form.output;
  EXPECT_THAT(form.output, HasSubstr("--case: case '640x484': expected WIDTHxHEIGHT@RATE, e.g. "
                                     "640x484@60 (pixels, Hz)"));
  const auto range =
      run_tactile("bench live " + prints + " --case 640x484@5000 --out bench-live-none");
  EXPECT_EQ(range.exit_code, 2) << range.output;
  EXPECT_THAT(range.output, HasSubstr("case 640 x 484 px at 5000 Hz: sizes must be from 64 to "
                                      "4096 px, rates from 1 to 1000 Hz"));
  const auto both =
      run_tactile("bench live " + prints + " --quick --case 320x240@60 --out bench-live-none");
  EXPECT_NE(both.exit_code, 0) << both.output;
  EXPECT_THAT(both.output, HasSubstr("--quick excludes --case"));
}

// A held-out print the folder does not hold is a wrong value given, as --print is for bench live.
TEST(RangeErrors, BenchPrintsNamesAHeldOutPrintItDoesNotHave) {
  const std::string prints = tactile::test::test_data("polyu-hrf-pores").string();
  const auto r = run_tactile("bench prints " + prints + " --held-out abc --out bench-prints-none");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--held-out abc: " + prints + " holds no print image_abc"));
}

// Found by the second hostile-input run: each was accepted (a calibration or a movie of nothing
// but rest, a sweep that always passes) or failed later with a message not naming the option.
TEST(RangeErrors, OptionsANumberCanNoLongerEmptyOfMeaning) {
  const std::string strain = (demo_dir() / "strain.h5").string();
  const std::string movie = (demo_dir() / "movie.h5").string();
  const std::string dots = (demo_dir() / "frames" / "calibration" / "dot_grid.png").string();
  expect_readable_range_error("calibrate " + dots + " --out x.json --spacing-mm 1e308",
                              "--spacing-mm: 1e308 is out of range: must be from 0.01 to 10");
  expect_readable_range_error("calibrate " + dots + " --out x.json --spacing-mm 1e-300",
                              "--spacing-mm: 1e-300 is out of range");
  expect_readable_range_error("map " + strain + " --out x.h5 --gain 0",
                              "--gain: 0 is out of range: must be from 0.001 to 1000000");
  expect_readable_range_error("map " + strain + " --out x.h5 --gain -5",
                              "--gain: -5 is out of range");
  expect_readable_range_error("map " + strain + " --out x.h5 --gain 1e-300",
                              "--gain: 1e-300 is out of range");
  expect_readable_range_error(
      "play " + movie + " --headless --blade-full-scale-um 1e308",
      "--blade-full-scale-um: 1e308 is out of range: must be from 0.1 to 10000");
  expect_readable_range_error("bench capture --min-points 1e308",
                              "--min-points: 1e308 is out of range: must be from 0 to 1000000");
  expect_readable_range_error("bench capture --max-rms 1e-300",
                              "--max-rms: 1e-300 is out of range: must be from 1e-06 to 1");
}

// Found by the third hostile-input run: a start beyond the movie's end opened the window at
// the last frame as if nothing were wrong. Checked once the movie is read, before any window.
TEST(RangeErrors, ViewAtBeyondTheMovieNamesItsLength) {
  const auto path = demo_dir() / "movie.h5";
  const auto movie = tactile::movie::read_tactile_movie(path);
  const std::string lasts = fmt::format("{:g}", movie.frame_count / movie.rate_hz);
  ASSERT_GT(movie.frame_count / movie.rate_hz, 1.0);
  for (const std::string at : {"12.5", "1e308", "+1e300"}) {
    expect_readable_range_error("view " + path.string() + " --at " + at,
                                "--at: " + fmt::format("{:g}", std::stod(at)) +
                                    " is out of range: " + path.string() + " lasts " + lasts +
                                    " s (0 to " + lasts + ")");
  }
  for (const char* at : {"nan", "-nan", "inf", "-inf", "-1e-300"}) {
    const auto r = run_tactile("view " + path.string() + " --at " + at);
    EXPECT_EQ(r.exit_code, 2) << at << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("--at")) << at;
  }
}

TEST(RangeErrors, HelpShowsReadableBounds) {
  const auto r = run_tactile("capture --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--px-per-mm FLOAT:2 to 5000"));
  EXPECT_THAT(r.output, HasSubstr("--span INT:1 to 10000"));
  for (const char* command : {"synth", "calibrate", "features", "capture", "train-pores", "map",
                              "perceive", "play", "view", "bench stream", "bench map"}) {
    const auto help = run_tactile(std::string(command) + " --help");
    EXPECT_FALSE(std::regex_search(help.output, std::regex("[0-9]{20}"))) << command;
  }
}

}  // namespace
