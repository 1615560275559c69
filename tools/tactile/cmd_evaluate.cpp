// `tactile evaluate`: a measured strain movie against the ground truth of a `tactile synth`
// folder (edge-strain error, localisation, yield, track lengths).

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "own_options.hpp"
#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_evaluate(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path sequence_dir;
    fs::path strain;
    std::optional<fs::path> csv_dir;
    bool per_frame = false;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "evaluate",
      "Compare a strain movie (from `tactile capture` on a `tactile synth` folder) with the\n"
      "folder's exact ground truth: RMS error of each edge's relative length change (overall\n"
      "and by frame), landmark localisation error, tracked landmarks per frame, track lengths.");
  add_input_folder(*sub, "SEQ_DIR", opt->sequence_dir, "Folder written by `tactile synth`");
  add_input_file(*sub, "STRAIN", opt->strain, "Strain movie (HDF5) measured on that folder");
  sub->add_option("--csv", opt->csv_dir,
                  "Write evaluation_frames.csv and evaluation_summary.csv into this folder");
  sub->add_flag("--per-frame", opt->per_frame, "Print the table for every frame pair");
  sub->callback([opt, &action] {
    action = [opt] {
      if (opt->csv_dir) {
        refuse_output_over_input(
            {output_folder("--csv", *opt->csv_dir,
                           {"evaluation_frames.csv", "evaluation_summary.csv"})},
            {{"SEQ_DIR", opt->sequence_dir / "scene.json"},
             {"SEQ_DIR", opt->sequence_dir / "landmarks.csv"},
             {"STRAIN", opt->strain}});
      }
      const capture::GroundTruth truth = capture::read_ground_truth(opt->sequence_dir);
      const capture::StrainMovie movie = capture::read_strain_movie(opt->strain);
      const int truth_frames = capture::truth_frame_count(truth);
      if (movie.camera_frame_count != truth_frames) {
        fmt::print(stderr, "evaluate: warning: the movie has {} camera frames, the sequence {}\n",
                   movie.camera_frame_count, truth_frames);
      }
      const capture::Evaluation ev = capture::evaluate_strain(movie, truth);
      if (opt->per_frame) {
        fmt::print("{:>6} {:>6} {:>6} {:>10} {:>10} {:>8} {:>8}\n", "from", "to", "edges",
                   "rms_error", "rms_truth", "tracked", "truth");
        for (const auto& f : ev.frames) {
          fmt::print("{:>6} {:>6} {:>6} {:>10.5f} {:>10.5f} {:>8} {:>8}", f.frame_from, f.frame_to,
                     f.edges, f.rms_error, f.rms_truth, f.tracked_points, f.truth_landmarks);
          if (ev.has_gap) {
            fmt::print("  in contact {:>6} {:>10.5f}", f.edges_in_contact, f.rms_error_in_contact);
          }
          fmt::print("\n");
        }
      }
      const std::string scene =
          truth.warp ? fmt::format("{} warp of the print {}",
                                   capture::to_string(truth.warp->pattern), truth.warp->source)
                     : to_string(truth.spec.scene);
      fmt::print("evaluate: scene {} ({} frames), {} strain frames, span {}\n", scene, truth_frames,
                 movie.frames.size(), movie.span_frames);
      fmt::print("  edge strain RMS error      {:.5f}  (true strain RMS {:.5f}, {} edges)\n",
                 ev.rms_error, ev.rms_truth, ev.edges);
      fmt::print("  correlation with truth     {:.4f}\n", ev.correlation);
      if (ev.has_gap) {
        fmt::print(
            "  in full contact            RMS error {:.5f}, correlation {:.4f}  ({} edges; {} "
            "edges across the contact gap{})\n",
            ev.rms_error_in_contact, ev.correlation_in_contact, ev.edges_in_contact,
            ev.edges_across_gap,
            ev.edges_across_gap_opening > 0
                ? fmt::format(", {} of them in a frame where it opens", ev.edges_across_gap_opening)
                : std::string());
      }
      if (ev.contact_cells > 0) {
        fmt::print(
            "  contact map                right on {:.1f}% of {} cells; out of contact ({} cells "
            "in "
            "the truth): overlap {:.2f}\n",
            100 * ev.contact_agreement, ev.contact_cells, ev.gap_cells, ev.gap_overlap);
      } else if (ev.has_gap) {
        fmt::print("  contact map                none in the strain movie\n");
      }
      fmt::print("  localisation RMS           {:.4f} mm  ({} points within {} mm, {} not)\n",
                 ev.localisation_rms_mm, ev.located_points, ev.match_bound_mm, ev.unmatched_points);
      fmt::print("  tracked landmarks / frame  median {:.0f}  (median yield {:.2f} of the true)\n",
                 ev.median_tracked_points, ev.median_yield);
      fmt::print("  tracks                     {}  (length median {:.0f}, mean {:.1f} frames)\n",
                 ev.track_count, ev.median_track_frames, ev.mean_track_frames);
      if (opt->csv_dir) {
        // The per-frame table and its summary replace the old pair together.
        CommitTogether together;
        capture::write_evaluation_csv(*opt->csv_dir, ev);
        together.commit();
        fmt::print("evaluate: wrote evaluation_frames.csv and evaluation_summary.csv in {}\n",
                   opt->csv_dir->string());
      }
      return 0;
    };
  });
}

}  // namespace tactile::cli
