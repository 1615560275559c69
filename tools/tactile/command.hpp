#pragma once
// How subcommands plug into the `tactile` program: each add_* function registers its options on
// a CLI11 subcommand and, when that subcommand is chosen, stores the work to run in `action`.
// Parsing and running are separate so that usage errors (exit 2) never start any work. Commands
// that write a file with a provenance take the command line as typed, for it.

#include <CLI/CLI.hpp>

#include <array>
#include <functional>
#include <string>

namespace tactile::cli {

using Action = std::function<int()>;

// The work of a command whose first steps make a StopSignals (before any long work). `tactile`
// blocks SIGINT and SIGTERM from its start; for such a command it keeps them blocked into the
// work, so that a signal sent while the command sets out waits for the StopSignals and becomes
// its stop request. Any other command gets the signals unblocked as `tactile` was started, and
// a Ctrl-C during its work ends it by the default action.
struct WatchingStopSignals {
  std::function<int()> run;
  int operator()() const { return run(); }
};

// Every command registers alike; `command_line` is the command line as typed, for the provenance
// of the files a command writes (a command that writes none leaves it unused).
using AddCommand = void(CLI::App& parent, Action& action, const std::string& command_line);

AddCommand add_demo, add_synth, add_calibrate, add_features, add_capture, add_train_pores,
    add_evaluate, add_map, add_experiment, add_perceive, add_classify, add_play, add_view,
    add_author, add_devices, add_info, add_export, add_import, add_emulate, add_live, add_bench;
AddCommand add_bench_map, add_bench_capture, add_bench_prints, add_bench_stream, add_bench_perceive,
    add_bench_latero, add_bench_live;

// The commands in the order `tactile --help` lists them.
inline constexpr std::array<AddCommand*, 21> kCommands = {
    &add_demo,     &add_synth,  &add_calibrate,  &add_features, &add_capture,  &add_train_pores,
    &add_evaluate, &add_map,    &add_experiment, &add_perceive, &add_classify, &add_play,
    &add_view,     &add_author, &add_devices,    &add_info,     &add_export,   &add_import,
    &add_emulate,  &add_live,   &add_bench};
inline constexpr std::array<AddCommand*, 7> kBenchmarks = {
    &add_bench_map,      &add_bench_capture, &add_bench_prints, &add_bench_stream,
    &add_bench_perceive, &add_bench_latero,  &add_bench_live};

}  // namespace tactile::cli
