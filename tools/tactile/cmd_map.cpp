// `tactile map`: strain movie -> tactile movie on a contactor layout.

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "request_options.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/fidelity.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/mapping/map_request.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_map(CLI::App& app, Action& action, const std::string& command_line) {
  const auto [request, sub] = add_request_command<mapping::MapRequest>(
      app, "map",
      "Map a strain movie (from `tactile capture`) onto a contactor layout: sample the strain\n"
      "at each contactor, turn it into deflections with the chosen method, resample to the\n"
      "display rate, clamp and slew-limit as the firmware will.",
      mapping::map_options());
  auto csv = std::make_shared<std::optional<fs::path>>();
  auto out = std::make_shared<fs::path>();
  sub->add_option("--out", *out, "Tactile movie to write (HDF5)")->required();
  sub->add_option("--csv", *csv, "Also export the movie as CSV");
  sub->callback([request, out, csv, &action, &command_line] {
    action = [request, out, csv, &command_line] {
      std::vector<NamedPath> inputs = {{"STRAIN_H5", request->strain}};
      if (fs::path(request->layout).extension() == ".json") {
        inputs.push_back({"--layout", request->layout});
      }
      std::vector<Output> outputs = {output_file("--out", *out)};
      if (*csv) outputs.push_back(output_file("--csv", **csv));
      refuse_output_over_input(outputs, inputs);
      // Before reading: fail fast on bad parameters.
      mapping::ResolvedMap resolved = mapping::resolve(*request, OptionSpelling::cli);
      const capture::StrainMovie strain = capture::read_strain_movie(request->strain);
      if (strain.frames.empty()) {
        throw std::runtime_error(fmt::format("map: {}: the strain movie has no strain frames",
                                             request->strain.string()));
      }
      mapping::check_against_strain(resolved, strain, request->strain.string(),
                                    OptionSpelling::cli);
      const auto t0 = std::chrono::steady_clock::now();
      resolved.params.program_version = kVersion;
      const capture::StrainMovie source = mapping::strain_source(strain, resolved.params);
      mapping::MappingResult result =
          mapping::map_strain_frames(source, resolved.layout, resolved.params);
      movie::TactileMovie& movie = result.movie;
      const double ms =
          1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      movie.provenance.input = request->strain.string();
      movie.provenance.command_line = command_line;
      // The movie and its CSV export replace the old pair together: a run stopped while it
      // writes the CSV must not leave a new movie beside the old CSV.
      CommitTogether together;
      movie::write_tactile_movie(*out, movie);
      if (*csv) movie::export_tactile_csv(**csv, movie);
      together.commit();
      fmt::print(
          "map: {} strain frames -> {} movie frames of {} x {} at {:g} Hz ({:.2f} s) in {:.1f} ms "
          "-> "
          "{}\n",
          strain.frames.size(), movie.frame_count, resolved.layout.rows, resolved.layout.cols,
          movie.rate_hz, movie.duration_s(), ms, out->string());
      if (*csv) fmt::print("map: wrote {}\n", (*csv)->string());
      const mapping::FidelityMetrics fit =
          mapping::fidelity(movie, source, result.placement, result.um_per_strain,
                            resolved.params.slew_limit_um_per_s, resolved.params.field);
      fmt::print("map: {}\n", mapping::describe_fidelity(fit));
      return 0;
    };
  });
}

}  // namespace tactile::cli
