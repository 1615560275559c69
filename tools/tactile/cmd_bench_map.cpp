// `tactile bench map`: how long the mapping of a demo-sized strain movie takes (target:
// 180 frames of about 500 landmarks onto 10 x 10 at 700 Hz in <= 50 ms).

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/author/outcome.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/mapping/bench.hpp"
#include "tactile/mapping/map_request.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::cli {

void add_bench_map(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    int repeats = 7;
    int frames = 180;
    double spacing_mm = 0.34;
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "map",
      "Time the mapping of a synthetic strain movie (the bump scene's exact strain on a\n"
      "landmark grid, Delaunay-triangulated like a measured movie) onto STReSS 10 x 10 at\n"
      "700 Hz, for every method; target <= 50 ms per 180-frame movie.");
  add_ranged(*sub, "--repeats", opt->repeats, "Timed repetitions (the median is reported)", 1,
             1000);
  add_ranged(*sub, "--frames", opt->frames, "Camera frames of the strain movie", 2, 100000);
  add_ranged(*sub, "--spacing-mm", opt->spacing_mm, "Landmark spacing (0.34 mm: ~500 per frame)",
             0.1, 5.0);
  sub->callback([opt, &action] {
    action = [opt] {
      capture::SceneSpec spec;
      spec.frame_count = opt->frames + 1;
      const auto movie = mapping::bench_strain_movie(spec, opt->spacing_mm);
      const auto layout = movie::stress_layout();
      fmt::print("{}",
                 mapping::map_bench_heading(movie, layout, std::thread::hardware_concurrency()));
      fmt::print("{}", mapping::map_bench_table_header());
      mapping::bench_mapping(movie, spec, layout, opt->repeats, [](const mapping::MapBenchRow& r) {
        fmt::print("{}", mapping::map_bench_table_row(r));
      });
      fmt::print(
          "(accumulated: time of the mapping after accumulate_along_tracks; target "
          "<= 50 ms per movie)\n");
      // What a change in `tactile author` waits for before it is drawn: the mapping and its
      // figures (fidelity whole and over time, limits per contactor), target <= 100 ms.
      std::vector<double> map_ms, figures_ms, total_ms;
      for (int r = 0; r < opt->repeats; ++r) {
        const Stopwatch clock;
        const author::MappingOutcome o = author::map_for_authoring(movie, mapping::MapRequest{});
        if (!o.error.empty()) throw std::runtime_error("bench map: authoring: " + o.error);
        total_ms.push_back(1e3 * clock.wall_s());
        map_ms.push_back(o.map_ms);
        figures_ms.push_back(o.figures_ms);
      }
      fmt::print(
          "authoring re-map (integrated, per-frame, with its figures): median {:.1f} ms "
          "(mapping {:.1f} + figures {:.1f}), max {:.1f} ms; target <= 100 ms from a change to "
          "its view\n",
          median(total_ms), median(map_ms), median(figures_ms),
          *std::max_element(total_ms.begin(), total_ms.end()));
      return 0;
    };
  });
}

}  // namespace tactile::cli
