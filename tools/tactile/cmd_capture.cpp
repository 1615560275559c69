// `tactile calibrate`, `tactile features` and `tactile capture`: the camera side of the pipeline.

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <string>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "progress.hpp"
#include "request_options.hpp"
#include "tactile/capture/calibrate.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/capture_request.hpp"
#include "tactile/capture/capture_run.hpp"
#include "tactile/capture/features.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/capture/strain_map.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/capture/video.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/common/version.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

// --calib FILE or --px-per-mm P, exactly one (see require_calibration). A calibration file is
// read before any image so that a bad file fails at once, before heavy work.
std::optional<capture::Calibration> calibration_file(const std::optional<fs::path>& calib_file) {
  if (calib_file) return capture::read_calibration_json(*calib_file);
  return std::nullopt;
}

capture::Calibration calibration_for(const std::optional<capture::Calibration>& from_file,
                                     std::optional<double> px_per_mm, int width_px, int height_px) {
  if (from_file) return *from_file;
  return capture::uniform_calibration(px_per_mm.value(), width_px, height_px);
}

void add_calibration_options(CLI::App& sub, std::optional<fs::path>& calib_file,
                             std::optional<double>& px_per_mm) {
  auto* c = sub.add_option("--calib", calib_file, "Calibration JSON from `tactile calibrate`")
                ->check(CLI::ExistingFile);
  auto* p = sub.add_option("--px-per-mm", px_per_mm,
                           "Uniform scale instead of a calibration file (pixels per millimetre)")
                ->check(within(capture::kMinPxPerMm, capture::kMaxPxPerMm));
  c->excludes(p);
}

// Runs at parse time so that a missing choice is a usage error (exit 2), not a failed run.
void require_calibration(const std::optional<fs::path>& calib_file,
                         const std::optional<double>& px_per_mm) {
  if (!calib_file && !px_per_mm) {
    throw CLI::RequiredError("one of --calib FILE or --px-per-mm P");
  }
}

// --pores paper|ridge-blob: the paper's binarised blobs (fast, for sequences) or the learned
// ridge-blob detector (for real high-resolution prints, about 0.1 s CPU per 320 x 240 print);
// --pore-model: a model from `tactile train-pores` instead of the shipped one.
void add_pore_options(CLI::App& sub, std::string& pores, std::optional<fs::path>& pore_model,
                      bool with_auto = false) {
  sub.add_option("--pores", pores,
                 std::string("Pore detector: paper (binarised blobs; fast) or ridge-blob (bright "
                             "spots above\ntheir own ridge, kept by a pore model trained on "
                             "hand-marked 1200 dpi prints;\nfinds open pores on real prints at "
                             "about 47 px/mm, slower)") +
                     (with_auto ? "; auto: the one that finds more pores\non the first frame "
                                  "(printed)"
                                : ""))
      ->check(with_auto ? CLI::IsMember({"auto", "paper", "ridge-blob"})
                        : CLI::IsMember({"paper", "ridge-blob"}))
      ->capture_default_str();
  sub.add_option("--pore-model", pore_model,
                 "Pore model file from `tactile train-pores` (with --pores ridge-blob), used\n"
                 "with its threshold instead of the shipped model")
      ->check(CLI::ExistingFile);
}

// Runs at parse time: the paper's rule has no model, so a model given with it would be ignored.
void require_ridge_blob_for_model(const std::string& pores,
                                  const std::optional<fs::path>& pore_model) {
  if (pore_model && pores == "paper") {
    throw CLI::ValidationError("--pore-model",
                               "goes with --pores ridge-blob (the paper's rule has no model)");
  }
}

// Read before any image so that a bad model file fails at once, before heavy work.
std::optional<capture::PoreModelFile> pore_model_file(const std::optional<fs::path>& path) {
  if (path) return capture::read_pore_model_json(*path);
  return std::nullopt;
}

// The chosen pore detector (and model) in `fp`; px_per_mm is the image's scale.
void use_pore_detector(const std::string& pores, const std::optional<capture::PoreModelFile>& model,
                       double px_per_mm, const char* command, capture::FeatureParams& fp) {
  const std::string warning = capture::use_pore_detector(
      pores == "ridge-blob" ? capture::PoreDetector::ridge_blob : capture::PoreDetector::paper,
      model, px_per_mm, fp);
  if (!warning.empty()) fmt::print(stderr, "{}: warning: {}\n", command, warning);
}

// The image (or the folder and its frames), and the calibration and pore model files when given:
// what a command of this file reads.
std::vector<NamedPath> inputs_of(const char* image_option, const fs::path& image,
                                 const std::optional<fs::path>& calib,
                                 const std::optional<fs::path>& pore_model) {
  std::vector<NamedPath> inputs = {{image_option, image}};
  if (fs::is_directory(image)) {
    for (const auto& frame : capture::list_frames(image)) inputs.push_back({image_option, frame});
  }
  if (calib) inputs.push_back({"--calib", *calib});
  if (pore_model) inputs.push_back({"--pore-model", *pore_model});
  return inputs;
}

std::string map_name(int frame_from) {
  return fmt::format("strain_{:03d}.png", frame_from);
}

// The maps, written until `stop_fd` asks to stop, at the full scale `full_scale` (above 0).
// Their files are committed with the strain movie's (a CommitTogether is alive): a stop replaces
// none.
void write_maps(const fs::path& dir, const capture::StrainMovie& movie, double full_scale,
                Progress& progress, int stop_fd) {
  fs::create_directories(dir);
  const int total = static_cast<int>(movie.frames.size());
  for (int i = 0; i < total; ++i) {
    if (stop_requested(stop_fd)) return;
    const auto& frame = movie.frames[static_cast<std::size_t>(i)];
    capture::write_strain_map_png(dir / map_name(frame.frame_from), frame, movie.calibration,
                                  {.full_scale = full_scale});
    progress("maps", i + 1, total);
  }
  progress.finish();
}

// CPU time of the whole process (every thread), seconds: the machine may be shared, so the wall
// time alone says little about the pipeline's cost.
double process_cpu_s() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

}  // namespace

void add_calibrate(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path image;
    double spacing_mm = 0.5;
    fs::path out = "calibration.json";
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "calibrate",
      "Calibrate the camera from an image of the dot grid (0.5 mm pitch by default): the\n"
      "pixel-to-millimetre homography (perspective of the prism) and the mean scale.");
  add_input_file(*sub, "DOT_GRID_IMAGE", opt->image, "Image of the dot grid");
  // A grid of at least 4 x 4 dots in a fingertip camera's 5-50 mm field.
  add_ranged(*sub, "--spacing-mm", opt->spacing_mm, "Dot spacing in mm", 0.01, 10.0);
  sub->add_option("--out", opt->out, "Calibration file to write (JSON)")->capture_default_str();
  sub->callback([opt, &action] {
    action = [opt] {
      refuse_output_over_input({output_file("--out", opt->out)},
                               inputs_of("DOT_GRID_IMAGE", opt->image, {}, {}));
      const capture::GrayImage image = capture::read_image(opt->image);
      // The library knows the pixels, not the file: a user calibrating several images must
      // learn which one had no grid.
      const capture::Calibration c = [&] {
        try {
          return capture::calibrate_dot_grid(image, opt->spacing_mm);
        } catch (const std::bad_alloc&) {
          throw;
        } catch (const std::exception& e) {
          throw FormatError(fmt::format("{}: {}", opt->image.string(),
                                        capture::opencv_error_text(e).value_or(e.what())));
        }
      }();
      capture::write_calibration_json(opt->out, c);
      fmt::print("calibrate: {:.2f} px/mm ({:.4f} mm/px) over {} x {} px, {} -> {}\n",
                 1.0 / c.mm_per_px, c.mm_per_px, c.image_width_px, c.image_height_px, c.method,
                 opt->out.string());
      return 0;
    };
  });
}

void add_features(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path image;
    std::optional<fs::path> calib;
    std::optional<double> px_per_mm;
    std::optional<fs::path> csv;
    std::string pores = "paper";
    std::optional<fs::path> pore_model;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "features",
      "Find skin landmarks (sweat pores, valley endings, bifurcations) in one image, as in the\n"
      "first paper. Prints counts; --csv writes type,x_px,y_px,x_mm,y_mm,orientation_rad.");
  add_input_file(*sub, "IMAGE", opt->image, "Fingerprint image (ridges dark, valleys bright)");
  add_calibration_options(*sub, opt->calib, opt->px_per_mm);
  sub->add_option("--csv", opt->csv, "Write the features to this CSV file");
  add_pore_options(*sub, opt->pores, opt->pore_model);
  sub->callback([opt, &action] {
    require_calibration(opt->calib, opt->px_per_mm);
    require_ridge_blob_for_model(opt->pores, opt->pore_model);
    action = [opt] {
      if (opt->csv) {
        refuse_output_over_input({output_file("--csv", *opt->csv)},
                                 inputs_of("IMAGE", opt->image, opt->calib, opt->pore_model));
      }
      const auto from_file = calibration_file(opt->calib);
      const auto model = pore_model_file(opt->pore_model);
      const capture::GrayImage image = capture::read_image(opt->image);
      // Smaller, there is no ridge to find landmarks on, and "0 pores" read as a measurement.
      if (image.width_px < 16 || image.height_px < 16) {
        throw FormatError(fmt::format(
            "{}: the image is {}x{} px, too small to hold a fingerprint (need at least 16x16 px)",
            opt->image.string(), image.width_px, image.height_px));
      }
      if (from_file) {
        capture::check_calibration_fits(*from_file, image.width_px, image.height_px,
                                        opt->calib->string(), opt->image.string());
      }
      const capture::Calibration c =
          calibration_for(from_file, opt->px_per_mm, image.width_px, image.height_px);
      capture::FeatureParams fp;
      use_pore_detector(opt->pores, model, 1.0 / c.mm_per_px, "features", fp);
      const auto features = capture::extract_features(image, 1.0 / c.mm_per_px, fp);
      int counts[3] = {0, 0, 0};
      for (const auto& f : features) ++counts[static_cast<int>(f.type)];
      fmt::print("features: {} pores, {} endings, {} bifurcations in {}\n", counts[0], counts[1],
                 counts[2], opt->image.string());
      if (opt->csv) {
        capture::write_features_csv(*opt->csv, features, c);
        fmt::print("features: wrote {}\n", opt->csv->string());
      }
      return 0;
    };
  });
}

void add_capture(CLI::App& app, Action& action, const std::string& command_line) {
  // What only the command line has: where the results go.
  struct Outputs {
    fs::path out;
    std::optional<fs::path> csv_dir;
    std::optional<fs::path> maps_dir;
  };
  const auto [request, sub] = add_request_command<capture::CaptureRequest>(
      app, "capture",
      "Measure skin strain from a sequence of fingerprint images (the image files of IMAGE_DIR\n"
      "in name order, or the frames of a video .mp4 .avi .mkv .mov): extract landmarks, match\n"
      "and track them, triangulate (Delaunay) and write each edge's relative length change\n"
      "between frames i and i+span. Frames are read one at a time.",
      capture::capture_options());
  auto outputs = std::make_shared<Outputs>();
  sub->add_option("--out", outputs->out, "Strain movie to write (HDF5)")->required();
  sub->add_option("--csv", outputs->csv_dir,
                  "Also write tracks.csv and edges.csv into this folder");
  sub->add_option("--maps", outputs->maps_dir,
                  "Also draw each strain frame as strain_NNN.png in this folder (edges black = "
                  "most compressed .. white = most stretched, one scale for the whole movie)");
  sub->callback([request, outputs, &action, &command_line] {
    capture::check_request(*request, OptionSpelling::cli);
    action = WatchingStopSignals{[request, outputs, &command_line] {
      // Before the first thread (OpenCV's workers, FFmpeg's readers), which inherit the block:
      // a stop signal is then a request, taken at the next progress step, and not a thread's
      // default action that ends the process while its outputs are half replaced.
      StopSignals stop;
      capture::ResolvedCapture run = capture::resolve(*request, OptionSpelling::cli);
      const capture::FrameRange& input = *run.frames;
      const auto inputs =
          inputs_of("IMAGE_DIR", request->source, request->calib, request->pore_model);
      std::vector<Output> outs = {output_file("--out", outputs->out)};
      if (outputs->csv_dir) {
        outs.push_back(output_folder("--csv", *outputs->csv_dir, {"tracks.csv", "edges.csv"}));
      }
      if (outputs->maps_dir) {
        // One map per strain frame, named by its first camera frame: at most one per input frame.
        std::vector<fs::path> maps;
        for (int i = 0; i < input.count(); ++i) maps.emplace_back(map_name(i));
        outs.push_back(output_folder("--maps", *outputs->maps_dir, maps));
      }
      refuse_output_over_input(outs, inputs);
      // The maps are PNG images: drawn among the frames, the next capture of the folder would
      // read them as frames of the sequence.
      if (outputs->maps_dir && !input.is_video() &&
          same_file(*outputs->maps_dir, request->source)) {
        throw OutputIsInputError(fmt::format(
            "--maps {} is the frames folder IMAGE_DIR: its strain_NNN.png images would become "
            "frames of the next capture of it; draw them into another folder",
            outputs->maps_dir->string()));
      }
      Progress progress;
      const capture::CaptureMessages messages{
          .note = [](const std::string& text) { fmt::print("capture: {}\n", text); },
          .warning =
              [](const std::string& text) { fmt::print(stderr, "capture: warning: {}\n", text); }};
      const auto t0 = std::chrono::steady_clock::now();
      const double cpu0 = process_cpu_s();
      struct Stopped {
        std::string stage;
        int done, total;
      };
      capture::StrainMovie movie;
      try {
        movie = capture::capture_strain(*run.frames, run.calibration, run.px_per_mm, run.rate_hz,
                                        run.settings, messages,
                                        [&](const std::string& stage, int done, int total) {
                                          if (stop_requested(stop.fd()))
                                            throw Stopped{stage, done, total};
                                          progress(stage, done, total);
                                        });
      } catch (const Stopped& at) {
        progress.finish();
        const int signal = stop.received();
        fmt::print(stderr, "capture: stopped by {} at {} {}/{}: nothing written\n",
                   stop_signal_name(signal), at.stage, at.done, at.total);
        return exit_code_for_signal(signal);
      }
      progress.finish();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      // An empty strain movie maps to a still display: report the reason instead of writing it.
      if (capture::measured_no_strain(movie)) {
        throw std::runtime_error(
            fmt::format("{}; nothing written to {}",
                        capture::no_strain_reason(movie, run.settings, request->source),
                        outputs->out.string()));
      }
      const double cpu_s = process_cpu_s() - cpu0;
      const int n = movie.camera_frame_count;
      movie.provenance.input = request->source.string();
      movie.provenance.command_line = command_line;
      // The strain movie, its CSV files and its maps replace the old ones together or not at all;
      // a stop is taken between files (the maps can be hundreds, more than the temporary files a
      // signal handler could remove).
      CommitTogether together;
      capture::write_strain_movie(outputs->out, movie);
      if (outputs->csv_dir) {
        fs::create_directories(*outputs->csv_dir);
        capture::export_strain_csv(*outputs->csv_dir, movie);
      }
      const double full_scale = capture::strain_map_full_scale(movie);
      if (outputs->maps_dir && full_scale > 0) {
        write_maps(*outputs->maps_dir, movie, full_scale, progress, stop.fd());
      }
      if (const int signal = stop.received(); signal != 0) {
        fmt::print(stderr,
                   "capture: stopped by {} while writing its outputs: none of them was "
                   "replaced\n",
                   stop_signal_name(signal));
        return exit_code_for_signal(signal);
      }
      together.commit();
      fmt::print(
          "capture: {} frames in {:.2f} s ({:.0f} frames/s; CPU {:.2f} ms per frame), {} strain "
          "frames at {:.4g} Hz ({}) -> {}\n",
          n, s, n / s, 1e3 * cpu_s / n, movie.frames.size(), run.rate_hz, run.rate_from,
          outputs->out.string());
      if (const std::string note = capture::sliding_note(movie); !note.empty()) {
        fmt::print("{}\n", note);
      }
      if (outputs->csv_dir) {
        fmt::print("capture: wrote tracks.csv and edges.csv in {}\n", outputs->csv_dir->string());
      }
      if (outputs->maps_dir && full_scale > 0) {
        fmt::print("capture: wrote {} strain maps (full scale {:.2f} %) in {}\n",
                   movie.frames.size(), 100 * full_scale, outputs->maps_dir->string());
      } else if (outputs->maps_dir) {
        fmt::print("capture: no strain edges, so no maps written\n");
      }
      return 0;
    }};
  });
}

}  // namespace tactile::cli
