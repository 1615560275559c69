// `tactile capture VIDEO`: a lossless video made here gives the strain of the folder of its
// frames, at the container's frame rate; --start/--frames pick the same part of either; a range
// beyond the video is a usage error and a damaged or foreign file a failure naming it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/capture/video.hpp"

namespace {

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;
namespace capture = tactile::capture;

// Every edge's strain, frame by frame, keyed by its two tracks.
std::vector<std::map<std::pair<int, int>, double>> strain_of(const fs::path& movie_file) {
  const auto movie = capture::read_strain_movie(movie_file);
  std::vector<std::map<std::pair<int, int>, double>> frames;
  for (const auto& f : movie.frames) {
    auto& edges = frames.emplace_back();
    for (const auto& e : f.edges) {
      edges[{std::min(e.track_a, e.track_b), std::max(e.track_a, e.track_b)}] = e.rel_change;
    }
  }
  return frames;
}

class CaptureVideo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto print =
        capture::read_image(tactile::test::test_data("polyu-hrf-pores") / "image_12.jpg");
    capture::PrintWarpSpec spec;
    spec.width_px = print.width_px;
    spec.height_px = print.height_px;
    spec.pattern = capture::WarpPattern::bump;
    spec.strain = 0.04;
    spec.frame_count = 12;
    const auto frames = capture::render_print_sequence(spec, print, {}).frames;
    capture::write_frames(dir_.path() / "frames", frames);
    capture::write_lossless_video(video_, frames, 30);
  }
  std::string capture_args(const fs::path& input, const std::string& out) const {
    return "capture " + input.string() + " --px-per-mm 47 --min-track 10 --out " +
           (dir_.path() / out).string();
  }

  tactile::test::TempDir dir_{"video"};
  fs::path video_ = dir_.path() / "print.mkv";
};

TEST_F(CaptureVideo, GivesTheStrainOfItsFramesAtTheContainersRate) {
  const auto from_frames =
      run_tactile(capture_args(dir_.path() / "frames", "frames.h5") + " --rate-hz 30");
  ASSERT_EQ(from_frames.exit_code, 0) << from_frames.output;
  const auto from_video = run_tactile(capture_args(video_, "video.h5"));
  ASSERT_EQ(from_video.exit_code, 0) << from_video.output;
  EXPECT_THAT(from_video.output, HasSubstr("12 frames"));
  EXPECT_THAT(from_video.output, HasSubstr("at 30 Hz"));
  EXPECT_EQ(capture::read_strain_movie(dir_.path() / "video.h5").frame_rate_hz, 30);
  const auto expected = strain_of(dir_.path() / "frames.h5");
  ASSERT_EQ(expected.size(), 11u);
  EXPECT_GT(expected[5].size(), 300u);
  EXPECT_EQ(strain_of(dir_.path() / "video.h5"), expected);
}

TEST_F(CaptureVideo, StartAndFramesPickThePartOfTheFolder) {
  const std::string part = " --start 2 --frames 10";
  ASSERT_EQ(run_tactile(capture_args(dir_.path() / "frames", "frames.h5") + part).exit_code, 0);
  const auto r = run_tactile(capture_args(video_, "video.h5") + part);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("10 frames"));
  const auto expected = strain_of(dir_.path() / "frames.h5");
  ASSERT_EQ(expected.size(), 9u);
  EXPECT_EQ(strain_of(dir_.path() / "video.h5"), expected);
}

TEST_F(CaptureVideo, ARangeBeyondTheVideoIsAUsageError) {
  auto r = run_tactile(capture_args(video_, "x.h5") + " --start 12");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--start: 12 is out of range"));
  EXPECT_THAT(r.output, HasSubstr("has 12 frames"));
  r = run_tactile(capture_args(video_, "x.h5") + " --start 4 --frames 9");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--frames: 9 is out of range"));
  EXPECT_FALSE(fs::exists(dir_.path() / "x.h5"));
}

TEST_F(CaptureVideo, DamagedOrForeignVideoFailsNamingTheFile) {
  const fs::path cut = dir_.path() / "cut.mkv";
  fs::copy_file(video_, cut);
  fs::resize_file(cut, fs::file_size(cut) / 2);
  auto r = run_tactile(capture_args(cut, "x.h5"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr(cut.string() + ": frame "));
  EXPECT_THAT(r.output, HasSubstr("truncated"));

  const fs::path garbage = dir_.path() / "garbage.avi";
  std::ofstream(garbage) << std::string(4000, 'x');
  r = run_tactile(capture_args(garbage, "x.h5"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr(garbage.string()));
  EXPECT_FALSE(fs::exists(dir_.path() / "x.h5"));
}

}  // namespace
