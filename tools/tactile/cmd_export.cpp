// `tactile export` and `tactile import`: tactile movies to and from files other tools read
// (MPEG-I Haptics HJIF, multichannel WAV). The formats live in the movie library.

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "request_options.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/version.hpp"
#include "tactile/movie/export_request.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_export(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  const auto [request, sub] = add_request_command<movie::ExportRequest>(
      app, "export",
      "Write a tactile movie in formats other tools read: MPEG-I Haptics (.hjif, one Position\n"
      "channel per contactor) or a multichannel float WAV (one channel per contactor).\n"
      "Mapping and what is lost: docs/formats.md.",
      movie::export_options());
  sub->callback([request, &action] {
    movie::check_request(*request, OptionSpelling::cli);
    action = [request] {
      movie::check_outputs(*request, OptionSpelling::cli);
      const movie::TactileMovie movie = movie::read_tactile_movie(request->movie);
      for (const auto& line : movie::run_export(*request, movie, OptionSpelling::cli).lines) {
        fmt::print("{}\n", line);
      }
      return 0;
    };
  });
}

void add_import(CLI::App& app, Action& action, const std::string& command_line) {
  struct Options {
    fs::path in;
    fs::path out;
    std::optional<std::string> layout;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "import",
      "Read an MPEG-I Haptics interchange file (.hjif) as a tactile movie: one Position\n"
      "perception whose channels target the contactors of a grid (docs/formats.md).");
  add_input_file(*sub, "IN_HJIF", opt->in, "MPEG-I Haptics interchange file");
  sub->add_option("--out", opt->out, "Tactile movie to write (HDF5)")->required();
  sub->add_option("--layout", opt->layout,
                  "Display layout: stress, stress2, latero or FILE.json (default: the layout the\n"
                  "file carries; required for files from other tools)");
  sub->callback([opt, &action, &command_line] {
    action = [opt, &command_line] {
      std::vector<NamedPath> inputs = {{"IN_HJIF", opt->in}};
      if (opt->layout && fs::path(*opt->layout).extension() == ".json") {
        inputs.push_back({"--layout", *opt->layout});
      }
      refuse_output_over_input({output_file("--out", opt->out)}, inputs);
      movie::HjifImportOptions options;
      if (opt->layout) options.layout = movie::resolve_layout(*opt->layout);
      movie::TactileMovie movie = movie::read_hjif(opt->in, options);
      // A file this program wrote carries the provenance of the movie it holds (with the
      // program's version); a file from another tool gets one that says it was imported.
      if (movie.provenance.program_version.empty()) {
        movie.provenance = make_provenance(opt->in.string(), "hjif import");
        movie.provenance.command_line = command_line;
      }
      movie::write_tactile_movie(opt->out, movie);
      fmt::print("import: {} x {} contactors ({}), {} frames at {:g} Hz ({:.2f} s) -> {}\n",
                 movie.layout.rows, movie.layout.cols, movie.layout.name, movie.frame_count,
                 movie.rate_hz, movie.duration_s(), opt->out.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
