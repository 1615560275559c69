// A capture run from a folder or a video; see capture_run.hpp.

#include "tactile/capture/capture_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tactile/capture/contact_strain.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {

namespace fs = std::filesystem;

FrameRange::FrameRange(const fs::path& source, int start, std::optional<int> count)
    : source_(source) {
  if (is_video_name(source) && !fs::is_directory(source)) {
    video_.emplace(source);
    total_ = video_->info().frame_count;
  } else {
    paths_ = list_frames(source);
    total_ = static_cast<int>(paths_.size());
  }
  start_ = start;
  count_ = count.value_or(total_ - start);
}

std::string FrameRange::range_error(OptionSpelling spelling) const {
  if (start_ < 0 || start_ >= total_) {
    return fmt::format("{}: {} is out of range: {} has {} frames (0 to {})",
                       option_label("start", spelling), start_, source_.string(), total_,
                       total_ - 1);
  }
  if (count_ < 1 || start_ + count_ > total_) {
    return fmt::format("{}: {} is out of range: from frame {} of {} there are {} frames",
                       option_label("frames", spelling), count_, start_, source_.string(),
                       total_ - start_);
  }
  return {};
}

bool FrameRange::next(GrayImage& frame) {
  if (read_ >= count_) return false;
  const int index = start_ + read_;
  if (video_) {
    video_->skip_to(index);
    if (!video_->read(frame)) return false;
  } else {
    const fs::path& path = paths_[static_cast<std::size_t>(index)];
    frame = read_image(path);
    if (read_ > 0 && (frame.width_px != width_px_ || frame.height_px != height_px_)) {
      throw FormatError(fmt::format(
          "{}: frame is {}x{} px but {} is {}x{} px; all frames of a sequence must have the "
          "same size",
          path.string(), frame.width_px, frame.height_px,
          paths_[static_cast<std::size_t>(start_)].filename().string(), width_px_, height_px_));
    }
  }
  width_px_ = frame.width_px;
  height_px_ = frame.height_px;
  ++read_;
  return true;
}

std::string to_string(PoreSetting setting) {
  return name_in(kPoreSettingNames, setting);
}
std::string to_string(RefineSetting setting) {
  return name_in(kRefineSettingNames, setting);
}

std::string use_pore_detector(PoreDetector detector, const std::optional<PoreModelFile>& model,
                              double px_per_mm, FeatureParams& features) {
  features.pore_detector = detector;
  if (!model) return {};
  features.ridge_blob.model = model->coefficients;
  features.ridge_blob.min_log_odds = model->min_log_odds;
  // The model's measures are in pixels at its training scale (sizes, Laplacian scales), so
  // far from that scale its probabilities mean little.
  if (std::abs(px_per_mm / model->px_per_mm - 1.0) > 0.1) {
    return fmt::format(
        "the pore model was trained at {:.1f} px/mm but the image is at {:.1f} px/mm; its "
        "measures are in pixels at the training scale",
        model->px_per_mm, px_per_mm);
  }
  return {};
}

StrainMovie capture_strain(FrameRange& frames, const std::optional<Calibration>& calibration,
                           std::optional<double> px_per_mm, double frame_rate_hz,
                           const CaptureSettings& settings, const CaptureMessages& messages,
                           const CaptureProgress& progress) {
  GrayImage first;
  frames.next(first);
  // Before any detection: a calibration for another image size maps every pixel wrong.
  if (calibration) {
    check_calibration_fits(*calibration, first.width_px, first.height_px,
                           settings.calibration_source, "the first frame");
  }
  const Calibration c =
      calibration ? *calibration
                  : uniform_calibration(px_per_mm.value(), first.width_px, first.height_px);
  CaptureParams params;
  params.span_frames = settings.span_frames;
  params.min_track_frames = settings.min_track_frames;
  PoreDetector detector =
      settings.pores == PoreSetting::ridge_blob ? PoreDetector::ridge_blob : PoreDetector::paper;
  // A pore model is a ridge-blob model: with one, auto means ridge-blob.
  if (settings.pores == PoreSetting::automatic && settings.pore_model) {
    detector = PoreDetector::ridge_blob;
  } else if (settings.pores == PoreSetting::automatic) {
    const CaptureChoice choice = choose_capture_settings(first, 1.0 / c.mm_per_px);
    detector = choice.detector;
    // Found with the default detector settings, which are the capture's here (no model).
    params.first_frame_features = choice.first_frame_features;
    messages.note(fmt::format(
        "pores: {} (on the first frame the paper's rule found {} pores, the ridge-blob detector "
        "{}; --pores overrides)",
        detector == PoreDetector::ridge_blob ? "ridge-blob" : "paper", choice.paper_pores,
        choice.ridge_blob_pores));
  }
  bool refine = settings.refine == RefineSetting::on;
  if (settings.refine == RefineSetting::automatic) {
    refine = refinement_for(detector);
    messages.note(fmt::format("refinement against the images: {} (--refine overrides)",
                              refine ? "on" : "off"));
  }
  params.refine = refine;
  params.refinement.window_mm = settings.refine_window_mm;
  params.smoothing_half_window =
      settings.smoothing_half_window.value_or(smoothing_half_window_for(refine));
  if (const std::string warning =
          use_pore_detector(detector, settings.pore_model, 1.0 / c.mm_per_px, params.features);
      !warning.empty()) {
    messages.warning(warning);
  }
  params.assignment = settings.assignment;
  // Where the skin touches, from every frame as it is read.
  params.measure_contact = true;
  bool first_given = false;
  StrainMovie movie = measure_strain(
      [&](GrayImage& frame) {
        if (first_given) return frames.next(frame);
        frame = std::move(first);
        first_given = true;
        return true;
      },
      c, frame_rate_hz, params, progress, frames.count());
  const auto edge_count = [](const StrainMovie& m) {
    std::size_t n = 0;
    for (const StrainFrame& f : m.frames) n += f.edges.size();
    return n;
  };
  const std::size_t measured = edge_count(movie);
  movie = strain_in_contact(std::move(movie));
  if (const std::size_t kept = edge_count(movie); kept < measured) {
    const auto settings = nlohmann::json::parse(movie.provenance.parameters_json, nullptr, false);
    messages.note(fmt::format(
        "contact: {} of {} strain edges left out, on tracks at or within {} cell ({} px) of skin "
        "the images show out of contact, in their frames or within {} frames of them (the "
        "tracks' smoothing), where the skin slides through the view",
        measured - kept, measured, kGapMarginCells, movie.contact.grid.cell_px,
        settings.value("smoothing_half_window_used", 0)));
  }
  return movie;
}

bool measured_no_strain(const StrainMovie& movie) {
  return std::all_of(movie.frames.begin(), movie.frames.end(),
                     [](const StrainFrame& f) { return f.edges.empty(); });
}

std::string sliding_note(const StrainMovie& movie) {
  if (!skin_slides_through_view(movie)) return {};
  const auto settings = nlohmann::json::parse(movie.provenance.parameters_json, nullptr, false);
  return fmt::format("capture: shortest track {} frames: {}; smoothing half-window {}: {}",
                     settings.value("min_track_frames_used", 0),
                     settings.value("min_track_reason", std::string()),
                     settings.value("smoothing_half_window_used", 0),
                     settings.value("smoothing_reason", std::string()));
}

std::string no_strain_reason(const StrainMovie& movie, const CaptureSettings& settings,
                             const fs::path& source) {
  return fmt::format(
      "capture: {}: no strain measured in {} frames (tracks of at least --min-track {} frames "
      "over --span {}: {} tracked points, {} strain frames with any edge between them)",
      source.string(), movie.camera_frame_count, settings.min_track_frames, settings.span_frames,
      movie.tracks.size(),
      std::count_if(movie.frames.begin(), movie.frames.end(),
                    [](const StrainFrame& f) { return !f.edges.empty(); }));
}

}  // namespace tactile::capture
