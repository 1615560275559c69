// `tactile map`: strain movie -> tactile movie on a contactor layout.

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "mode_option.hpp"
#include "number_checks.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_map(CLI::App& app, Action& action, const std::string& command_line) {
  struct Options {
    fs::path strain;
    fs::path out;
    std::string layout = "stress";
    mapping::MappingParams params;
    std::optional<fs::path> csv;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "map",
      "Map a strain movie (from `tactile capture`) onto a contactor layout: sample the strain\n"
      "at each contactor, turn it into deflections with the chosen method, resample to the\n"
      "display rate, clamp and slew-limit as the firmware will.");
  sub->add_option("STRAIN_H5", opt->strain, "Strain movie (HDF5)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", opt->out, "Tactile movie to write (HDF5)")->required();
  sub->add_option("--layout", opt->layout,
                  "Contactor layout: stress, stress2, latero, or a custom layout FILE.json\n"
                  "(schema in docs/formats.md)")
      ->capture_default_str();
  add_mode_option(*sub, "--method", opt->params.method, mapping::kMappingMethodNames,
                  "Mapping method. integrated (default): the deflection differences between\n"
                  "neighbouring contactors reproduce the measured strain; proportional: each\n"
                  "contactor deflects by its local strain, which does not impose that strain\n"
                  "(correlation 0.02-0.05 on the ground-truth scenes); profile: from a surface\n"
                  "profile (experiments only)");
  sub->add_option("--gain", opt->params.gain_um_per_strain,
                  "Micrometres of deflection per unit strain")
      // Positive, as mapping requires; below 0.001 every deflection rounds to rest.
      ->check(within(0.001, 1000000.0))
      ->capture_default_str();
  add_mode_option(*sub, "--normalise", opt->params.normalisation, mapping::kNormalisationNames,
                  "none: gain as given; peak: scale so the largest deflection fills the range;\n"
                  "p99: the same with the 99th percentile");
  add_mode_option(*sub, "--strain", opt->params.strain, mapping::kStrainModeNames,
                  "per-frame: the movie's strain frames as captured; accumulated: strain from\n"
                  "the reference frame along the tracks (contactors follow the skin)");
  sub->add_option("--reference-frame", opt->params.accumulate.reference_frame,
                  "Camera frame the accumulated strain starts from (-1: the first)")
      ->check(within(-1, 100000000))
      ->capture_default_str();
  sub->add_option("--rate-hz", opt->params.rate_hz,
                  "Display frame rate, a whole number of hertz (default: the layout's own rate,\n"
                  "e.g. stress 700 Hz, latero 750 Hz)")
      ->check(playable_rate());
  sub->add_option("--csv", opt->csv, "Also export the movie as CSV");
  sub->callback([opt, &action, &command_line] {
    action = [opt, &command_line] {
      std::vector<NamedPath> inputs = {{"STRAIN_H5", opt->strain}};
      if (fs::path(opt->layout).extension() == ".json") inputs.push_back({"--layout", opt->layout});
      std::vector<Output> outputs = {output_file("--out", opt->out)};
      if (opt->csv) outputs.push_back(output_file("--csv", *opt->csv));
      refuse_output_over_input(outputs, inputs);
      const movie::Layout layout = movie::resolve_layout(opt->layout);
      // Before reading: fail fast on bad parameters.
      mapping::resolve_mapping_params(opt->params, layout);
      const capture::StrainMovie strain = capture::read_strain_movie(opt->strain);
      if (strain.frames.empty()) {
        throw std::runtime_error(
            fmt::format("map: {}: the strain movie has no strain frames", opt->strain.string()));
      }
      const auto t0 = std::chrono::steady_clock::now();
      opt->params.program_version = kVersion;
      movie::TactileMovie movie = mapping::map_strain_movie(strain, layout, opt->params);
      const double ms =
          1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      movie.provenance.input = opt->strain.string();
      movie.provenance.command_line = command_line;
      // The movie and its CSV export replace the old pair together: a run stopped while it
      // writes the CSV must not leave a new movie beside the old CSV.
      CommitTogether together;
      movie::write_tactile_movie(opt->out, movie);
      if (opt->csv) movie::export_tactile_csv(*opt->csv, movie);
      together.commit();
      fmt::print(
          "map: {} strain frames -> {} frames of {} x {} at {:g} Hz ({:.2f} s) in {:.1f} ms -> "
          "{}\n",
          strain.frames.size(), movie.frame_count, layout.rows, layout.cols, movie.rate_hz,
          movie.duration_s(), ms, opt->out.string());
      if (opt->csv) fmt::print("map: wrote {}\n", opt->csv->string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
