// `tactile author`: the authoring window on a strain movie (author/author_window.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "latero_cli.hpp"
#include "request_options.hpp"
#include "tactile/author/author_window.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/plain_name.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/mapping/map_request.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

const char* target_name(display::PlaybackTarget target) {
  switch (target) {
    case display::PlaybackTarget::device:
      return "a display";
    case display::PlaybackTarget::window:
      return "the window";
    case display::PlaybackTarget::headless:
      return "the emulated device (headless)";
    case display::PlaybackTarget::latero:
      return "a Latero";
  }
  return "?";
}

}  // namespace

void add_author(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    std::optional<fs::path> experiment;
    fs::path out = "authored";
    std::string name = "authored";
    std::optional<fs::path> screenshot;
  };
  const auto [request, sub] = add_request_command<mapping::MapRequest>(
      app, "author",
      "Author a mapping in a window: the mapping's choices in a panel (those of `tactile map`),\n"
      "re-mapped in the background on every change, the strain and the contactor array side\n"
      "by side, the fidelity figures and their chart over time, contactors at a limit outlined.\n"
      "P pins the mapping as A, Tab switches A and B, Enter auditions on whatever `play` would\n"
      "choose (a display, else the emulated device; with --latero, that Latero), S saves A and\n"
      "B as an experiment that `tactile experiment` runs to the same movies. H lists every key.",
      mapping::map_options());
  auto opt = std::make_shared<Options>();
  auto latero = std::make_shared<display::LateroPlayTarget>();
  sub->add_option("--experiment", opt->experiment,
                  "Start from an experiment file's mappings (its first run as A, its last as the "
                  "current one; options given here change the current one)")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", opt->out,
                  "Folder Save writes into: NAME.json and movies/<run id>.h5 (.hjif, .wav)")
      ->capture_default_str();
  sub->add_option("--name", opt->name, "The saved experiment's name (a plain name)")
      ->capture_default_str();
  add_latero_play_options(*sub, *latero);
  sub->add_option("--screenshot", opt->screenshot,
                  "Draw the window once the mappings are made, write it to this PNG and quit");
  sub->callback([request, opt, latero, sub, &action] {
    action = [request, opt, latero, sub] {
      if (const auto problem = plain_name_error("--name", opt->name)) {
        throw RequestError(*problem);
      }
      std::vector<NamedPath> inputs = {{"STRAIN_H5", request->strain}};
      if (opt->experiment) inputs.push_back({"--experiment", *opt->experiment});
      std::vector<Output> outputs = {
          output_folder("--out", opt->out, {opt->name + ".json"}, {"movies"})};
      if (opt->screenshot) {
        outputs.push_back(output_file_ending("--screenshot", *opt->screenshot, ".png"));
      }
      refuse_output_over_input(outputs, inputs);

      mapping::MapRequest current = *request;
      std::optional<mapping::MapRequest> a;
      if (opt->experiment) {
        const author::ExperimentChoices choices =
            author::choices_of(experiments::read_experiment(*opt->experiment));
        a = choices.a;
        current = choices.current;
        current.strain = request->strain;
        if (a) a->strain = request->strain;
        // Options given on the command line change the experiment's current mapping.
        for (const auto& row : mapping::map_options()) {
          if (row.positional) continue;
          if (sub->count(option_label(row.name, OptionSpelling::cli)) > 0) {
            row.set(current, row.get(*request));
          }
        }
      }
      // Refused before the window opens, in the command line's words.
      (void)mapping::resolve(current, OptionSpelling::cli);
      if (!display::screen_available()) {
        throw std::runtime_error(
            "no screen (DISPLAY is unset or cannot be opened); `tactile map` and `tactile "
            "experiment` do the same work without a window");
      }
      auto strain =
          std::make_shared<const capture::StrainMovie>(capture::read_strain_movie(request->strain));
      if (strain->frames.empty()) {
        throw std::runtime_error(fmt::format("author: {}: the strain movie has no strain frames",
                                             request->strain.string()));
      }
      StopSignals stop;
      author::AuthorWindowOptions options;
      options.strain_file = request->strain;
      options.out_dir = opt->out;
      options.name = opt->name;
      options.screenshot = opt->screenshot;
      options.visible = !opt->screenshot;
      options.stop_fd = stop.fd();
      options.audition_backends = display::usb_play_backends();
      if (!latero->address.empty()) options.audition_latero = *latero;
      options.say = [](const std::string& line) {
        fmt::print("{}\n", line);
        std::fflush(stdout);
      };
      const author::AuthorWindowResult r = author::run_author_window(strain, current, a, options);
      const double fps =
          r.drawing_s > 0 ? static_cast<double>(r.frames_drawn - 1) / r.drawing_s : 0;
      std::string latency = "no change";
      if (!r.change_to_view_ms.empty()) {
        latency =
            fmt::format("change to view: median {:.0f} ms, max {:.0f} ms over {} mappings",
                        median(r.change_to_view_ms),
                        *std::max_element(r.change_to_view_ms.begin(), r.change_to_view_ms.end()),
                        r.change_to_view_ms.size());
      }
      fmt::print("author: {} frames drawn at {:.0f} frames/s; {}\n", r.frames_drawn, fps, latency);
      for (std::size_t i = 0; i < r.auditions.size(); ++i) {
        const auto& p = r.auditions[i];
        if (!p.report) continue;
        fmt::print(
            "author: audition {}: {} on {}: {} frames played, {} underruns, {} clamped, {} "
            "slew-limited samples, final max {:.1f} um\n",
            i + 1, p.stopped ? "stopped" : "played", target_name(p.target), p.report->frames_played,
            p.report->underruns, p.report->clamped_samples, p.report->slew_limited_samples,
            p.final_max_um);
      }
      return 0;
    };
  });
}

}  // namespace tactile::cli
