#pragma once
// How subcommands plug into the `tactile` program: each add_* function registers its options on
// a CLI11 subcommand and, when that subcommand is chosen, stores the work to run in `action`.
// Parsing and running are separate so that usage errors (exit 2) never start any work. Commands
// that write a file with a provenance take the command line as typed, for it.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace tactile::cli {

using Action = std::function<int()>;

void add_demo(CLI::App& app, Action& action, const std::string& command_line);
void add_synth(CLI::App& app, Action& action, const std::string& command_line);
void add_calibrate(CLI::App& app, Action& action);
void add_features(CLI::App& app, Action& action);
void add_capture(CLI::App& app, Action& action, const std::string& command_line);
void add_train_pores(CLI::App& app, Action& action);
void add_evaluate(CLI::App& app, Action& action);
void add_map(CLI::App& app, Action& action, const std::string& command_line);
void add_experiment(CLI::App& app, Action& action);
void add_perceive(CLI::App& app, Action& action);
void add_classify(CLI::App& app, Action& action);
void add_play(CLI::App& app, Action& action);
void add_view(CLI::App& app, Action& action);
void add_author(CLI::App& app, Action& action);
void add_devices(CLI::App& app, Action& action);
void add_info(CLI::App& app, Action& action);
void add_export(CLI::App& app, Action& action);
void add_import(CLI::App& app, Action& action, const std::string& command_line);
void add_emulate(CLI::App& app, Action& action);
void add_live(CLI::App& app, Action& action);
void add_bench(CLI::App& app, Action& action);
void add_bench_map(CLI::App& bench, Action& action);
void add_bench_capture(CLI::App& bench, Action& action);
void add_bench_prints(CLI::App& bench, Action& action);
void add_bench_stream(CLI::App& bench, Action& action);
void add_bench_perceive(CLI::App& bench, Action& action);
void add_bench_latero(CLI::App& bench, Action& action);
void add_bench_live(CLI::App& bench, Action& action);

}  // namespace tactile::cli
