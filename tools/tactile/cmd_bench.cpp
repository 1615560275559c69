// `tactile bench ...`: benchmarks that print figures (and write CSV and plots). Speed targets
// live here, not in unit tests. Each benchmark registers itself below.

#include "command.hpp"

namespace tactile::cli {

void add_bench(CLI::App& app, Action& action) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: print throughput and accuracy figures (see each one's --help).");
  bench->require_subcommand(1);
  add_bench_map(*bench, action);
  add_bench_capture(*bench, action);
  add_bench_prints(*bench, action);
  add_bench_stream(*bench, action);
  add_bench_perceive(*bench, action);
  add_bench_latero(*bench, action);
  add_bench_live(*bench, action);
}

}  // namespace tactile::cli
