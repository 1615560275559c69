// `tactile bench ...`: benchmarks that print figures (and write CSV and plots). Speed targets
// live here, not in unit tests. Each benchmark registers itself below.

#include "command.hpp"

namespace tactile::cli {

void add_bench(CLI::App& app, Action& action, const std::string& command_line) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: print throughput and accuracy figures (see each one's --help).");
  bench->require_subcommand(1);
  for (AddCommand* add : kBenchmarks) add(*bench, action, command_line);
}

}  // namespace tactile::cli
