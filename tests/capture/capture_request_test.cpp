// The capture request's rules, which the command line and the Python module both apply: one of
// a calibration and a scale, a pore model only with a detector that uses one, the frames' range
// against the input, and the rate from where it was given.

#include "tactile/capture/capture_request.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <set>

#include "../common/temp_dir.hpp"

namespace {

using tactile::OptionSpelling;
using tactile::RequestError;
using tactile::capture::CaptureRequest;
using ::testing::HasSubstr;

std::string error_of(const CaptureRequest& r, OptionSpelling spelling) {
  try {
    tactile::capture::resolve(r, spelling);
  } catch (const RequestError& e) {
    return e.what();
  }
  return {};
}

// Three 32 x 32 grey frames.
void write_frames(const std::filesystem::path& dir) {
  for (int i = 0; i < 3; ++i) {
    cv::imwrite((dir / fmt::format("f{}.png", i)).string(),
                cv::Mat(32, 32, CV_8UC1, cv::Scalar(40 * i)));
  }
}

// A request for three frames of a folder at 47 px/mm.
class CaptureRequestOn3Frames : public ::testing::Test {
 protected:
  void SetUp() override {
    write_frames(dir.path());
    r.source = dir.path();
    r.px_per_mm = 47;
  }
  tactile::test::TempDir dir{"request"};
  CaptureRequest r;
};

TEST_F(CaptureRequestOn3Frames, OneOfCalibrationAndScale) {
  r.px_per_mm.reset();
  EXPECT_EQ(error_of(r, OptionSpelling::cli),
            "give one of --calib (a calibration file) or --px-per-mm");
  EXPECT_EQ(error_of(r, OptionSpelling::python),
            "give one of calib (a calibration file) or px_per_mm");
  r.px_per_mm = 47;
  EXPECT_EQ(error_of(r, OptionSpelling::cli), "");
}

TEST_F(CaptureRequestOn3Frames, RangeOfFramesInTheFrontEndsWords) {
  r.start = 3;
  EXPECT_THAT(error_of(r, OptionSpelling::python), HasSubstr("start: 3 is out of range"));
  EXPECT_THAT(error_of(r, OptionSpelling::cli), HasSubstr("--start: 3 is out of range"));
  r.start = 1;
  r.frames = 3;
  EXPECT_THAT(error_of(r, OptionSpelling::cli), HasSubstr("--frames: 3 is out of range"));
}

TEST_F(CaptureRequestOn3Frames, ValuesSetByAProgramAreCheckedAsTyped) {
  r.px_per_mm = 1;  // set directly, not through the table
  EXPECT_EQ(error_of(r, OptionSpelling::python),
            "px_per_mm: 1 is out of range: must be from 2 to 5000");
}

TEST_F(CaptureRequestOn3Frames, PoreModelOnlyWithADetectorThatUsesOne) {
  r.pores = tactile::capture::PoreSetting::paper;
  r.pore_model = dir.path() / "model.json";
  EXPECT_THAT(error_of(r, OptionSpelling::cli), HasSubstr("--pore-model: goes with --pores"));
}

TEST_F(CaptureRequestOn3Frames, RateGivenElseTheDefaultForFrames) {
  auto run = tactile::capture::resolve(r, OptionSpelling::cli);
  EXPECT_EQ(run.rate_hz, tactile::capture::kCameraRateHz);
  EXPECT_EQ(run.frames->count(), 3);
  r.rate_hz = 120;
  r.min_track = 5;
  run = tactile::capture::resolve(r, OptionSpelling::cli);
  EXPECT_EQ(run.rate_hz, 120);
  EXPECT_EQ(run.rate_from, "given");
  EXPECT_EQ(run.settings.min_track_frames, 5);
}

TEST(CaptureRequest, TableNamesEveryOptionOnceAndShowsTheStructsDefaults) {
  const auto& table = tactile::capture::capture_options();
  std::set<std::string_view> names;
  for (const auto& row : table) EXPECT_TRUE(names.insert(row.name).second) << row.name;
  const auto* min_track = tactile::find_option(table, "min_track");
  ASSERT_NE(min_track, nullptr);
  EXPECT_EQ(min_track->shown(CaptureRequest{}),
            std::to_string(tactile::capture::TrackParams{}.min_track_frames));
}

}  // namespace
