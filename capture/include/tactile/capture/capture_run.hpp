#pragma once
// A capture run as `tactile capture` and the Python module's capture() make it: the frames of a
// folder or a video (a range of them, one at a time), the calibration, the pore detector and
// refinement (chosen on the first frame when asked to), then measure_strain.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/capture.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/capture/video.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/option_table.hpp"

namespace tactile::capture {

// The frames a capture reads: the image files of a folder in name order, or a video's frames,
// from `start` on and `count` of them (all to the end when not given), one at a time.
class FrameRange {
 public:
  // Throws tactile::FormatError naming the source when it cannot be listed or opened.
  FrameRange(const std::filesystem::path& source, int start, std::optional<int> count);
  bool is_video() const { return video_.has_value(); }
  int total() const { return total_; }
  int start() const { return start_; }
  int count() const { return count_; }
  double frame_rate_hz() const { return video_ ? video_->info().frame_rate_hz : 0.0; }

  // start and count against the input's length, naming the options as the front end spells them
  // (empty when they fit).
  std::string range_error(OptionSpelling spelling = OptionSpelling::cli) const;

  // The next frame of the range, or false after its last. Throws tactile::FormatError naming the
  // file when a frame cannot be read or differs in size from the first.
  bool next(GrayImage& frame);

 private:
  std::filesystem::path source_;
  std::optional<VideoReader> video_;
  std::vector<std::filesystem::path> paths_;
  int total_ = 0, start_ = 0, count_ = 0, read_ = 0;
  int width_px_ = 0, height_px_ = 0;
};

// Pore detector and refinement as asked for: a fixed one, or chosen on the first frame.
enum class PoreSetting { automatic, paper, ridge_blob };
enum class RefineSetting { automatic, on, off };
inline constexpr std::array<Named<PoreSetting>, 3> kPoreSettingNames = {{
    {PoreSetting::automatic, "auto"},
    {PoreSetting::paper, "paper"},
    {PoreSetting::ridge_blob, "ridge-blob"},
}};
inline constexpr std::array<Named<RefineSetting>, 3> kRefineSettingNames = {{
    {RefineSetting::automatic, "auto"},
    {RefineSetting::on, "on"},
    {RefineSetting::off, "off"},
}};
std::string to_string(PoreSetting setting);
std::string to_string(RefineSetting setting);

// The detector in `features`, with a pore model from `tactile train-pores` when given. Returns a
// warning for a person (empty: none) when the image's scale is far from the model's.
std::string use_pore_detector(PoreDetector detector, const std::optional<PoreModelFile>& model,
                              double px_per_mm, FeatureParams& features);

struct CaptureSettings {
  PoreSetting pores = PoreSetting::automatic;
  RefineSetting refine = RefineSetting::automatic;
  std::optional<int> smoothing_half_window;  // unset: smoothing_half_window_for(refine)
  double refine_window_mm = RefineParams{}.window_mm;
  int span_frames = 1;
  int min_track_frames = kMinTrackFrames;
  Assignment assignment = Assignment::greedy;
  std::optional<PoreModelFile> pore_model;  // a ridge-blob model (pores auto then means it)
  // Where the calibration came from (e.g. its file), named when it does not fit the frames
  // (without a file, the capture itself).
  std::string calibration_source = "capture";
};

// What a person is told while capturing: `note` (what auto chose), `warning`.
struct CaptureMessages {
  std::function<void(const std::string&)> note = [](const std::string&) {};
  std::function<void(const std::string&)> warning = [](const std::string&) {};
};

// Measures strain over `frames` (range already checked): the calibration file's when given, else
// the uniform px_per_mm over the first frame's size (one of the two must be given).
StrainMovie capture_strain(FrameRange& frames, const std::optional<Calibration>& calibration,
                           std::optional<double> px_per_mm, double frame_rate_hz,
                           const CaptureSettings& settings, const CaptureMessages& messages,
                           const CaptureProgress& progress = {});

// True when no strain frame holds an edge: no strain frames at all, or frames whose tracked
// points were too few or too close to triangulate (two 1 x 1 images, say). Such a movie maps to
// a still display, so callers refuse it with no_strain_reason.
bool measured_no_strain(const StrainMovie& movie);
// Why a capture of `source` measured no strain, for a person (in the words of `tactile capture`'s
// options).
// Where the skin slid through the view, the shortest track the capture kept and why, for a
// person; empty for a still contact (the shortest track is then the one asked for).
std::string sliding_note(const StrainMovie& movie);
std::string no_strain_reason(const StrainMovie& movie, const CaptureSettings& settings,
                             const std::filesystem::path& source);

}  // namespace tactile::capture
