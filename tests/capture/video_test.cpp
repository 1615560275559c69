// Video input: a lossless video made here reads back as its frames, gives the strain of the
// same frames held in memory, and a damaged or foreign file is refused naming the file (and
// the frame).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <utility>
#include <vector>

#include "../common/temp_dir.hpp"
#include "real_prints.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/video.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

// 12 frames of real print 12 under a 4 % bump (with slide, blur, noise and drift).
std::vector<GrayImage> print_frames() {
  const GrayImage print = read_image(test::print_path("12", "image_"));
  PrintWarpSpec spec = test::spec_for(print, WarpPattern::bump, 0.04);
  spec.frame_count = 12;
  return render_print_sequence(spec, print, {}).frames;
}

TEST(Video, LosslessVideoReadsBackAsItsFramesAndGivesTheSameStrain) {
  const tactile::test::TempDir dir("video");
  const auto frames = print_frames();
  const fs::path path = dir.path() / "print.mkv";
  write_lossless_video(path, frames, 60);

  VideoReader reader(path);
  EXPECT_EQ(reader.info().width_px, frames[0].width_px);
  EXPECT_EQ(reader.info().height_px, frames[0].height_px);
  EXPECT_DOUBLE_EQ(reader.info().frame_rate_hz, 60);
  ASSERT_EQ(reader.info().frame_count, 12);
  GrayImage frame;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_TRUE(reader.read(frame)) << i;
    EXPECT_EQ(frame.pixels, frames[i].pixels) << "frame " << i;
  }
  EXPECT_FALSE(reader.read(frame));

  CaptureParams params = with_choice({}, choose_capture_settings(frames[0], 47.0));
  ASSERT_TRUE(params.refine);
  params.min_track_frames = 10;
  const Calibration cal = uniform_calibration(47.0, frames[0].width_px, frames[0].height_px);
  const StrainMovie in_memory = measure_strain(frames, cal, 60, params);
  VideoReader streamed(path);
  const StrainMovie from_video =
      measure_strain([&](GrayImage& f) { return streamed.read(f); }, cal, 60, params);
  ASSERT_EQ(from_video.frames.size(), in_memory.frames.size());
  ASSERT_GT(in_memory.frames[5].edges.size(), 300u);
  // The triangulation lists a frame's edges in an order of its own: compared as sets.
  const auto edges_of = [](const StrainFrame& frame) {
    std::map<std::pair<int, int>, double> edges;
    for (const auto& e : frame.edges) {
      edges[{std::min(e.track_a, e.track_b), std::max(e.track_a, e.track_b)}] = e.rel_change;
    }
    return edges;
  };
  for (std::size_t f = 0; f < in_memory.frames.size(); ++f) {
    EXPECT_EQ(edges_of(in_memory.frames[f]), edges_of(from_video.frames[f])) << "frame " << f;
  }
}

TEST(Video, SkipsToAFrameByDecoding) {
  const tactile::test::TempDir dir("video");
  const auto frames = print_frames();
  const fs::path path = dir.path() / "print.mkv";
  write_lossless_video(path, frames, 30);
  VideoReader reader(path);
  EXPECT_DOUBLE_EQ(reader.info().frame_rate_hz, 30);
  reader.skip_to(7);
  GrayImage frame;
  ASSERT_TRUE(reader.read(frame));
  EXPECT_EQ(frame.pixels, frames[7].pixels);
  EXPECT_EQ(reader.position(), 8);
}

TEST(Video, TruncatedVideoNamesTheFileAndTheFrame) {
  const tactile::test::TempDir dir("video");
  const auto frames = print_frames();
  const fs::path path = dir.path() / "cut.mkv";
  write_lossless_video(path, frames, 60);
  fs::resize_file(path, fs::file_size(path) / 2);
  VideoReader reader(path);
  ASSERT_EQ(reader.info().frame_count, 12);
  GrayImage frame;
  int read = 0;
  try {
    while (reader.read(frame)) ++read;
    ADD_FAILURE() << "a video cut in half read to its end";
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr(path.string()), HasSubstr("frame " + std::to_string(read)),
                      HasSubstr("truncated")));
  }
  EXPECT_GT(read, 0);
  EXPECT_LT(read, 12);
}

TEST(Video, WhatIsNotAVideoIsRefusedNamingTheFile) {
  const tactile::test::TempDir dir("video");
  const fs::path garbage = dir.path() / "garbage.mp4";
  {
    std::ofstream out(garbage, std::ios::binary);
    for (int i = 0; i < 5000; ++i) out.put(static_cast<char>((i * 2654435761u) >> 24));
  }
  EXPECT_THAT([&] { VideoReader r(garbage); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr(garbage.string())));
  const fs::path missing = dir.path() / "missing.avi";
  EXPECT_THAT([&] { VideoReader r(missing); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr(missing.string())));
  EXPECT_TRUE(is_video_name("a/B.MKV"));
  EXPECT_TRUE(is_video_name("x.mp4"));
  EXPECT_FALSE(is_video_name("frame_000.png"));
}

}  // namespace
}  // namespace tactile::capture
