#pragma once
// What `tactile bench capture` and `tactile bench prints` share on their command lines: an output
// folder, the stability sweeps switch and the limits at which a sweep point fails.

#include <CLI/CLI.hpp>
#include <filesystem>

#include "number_checks.hpp"
#include "tactile/capture/bench.hpp"

namespace tactile::cli {

struct BenchSweepOptions {
  std::filesystem::path out;
  bool sweeps = false;
  capture::SweepLimits limits;
};

inline void add_bench_sweep_options(CLI::App& sub, BenchSweepOptions& opt) {
  sub.add_option("--out", opt.out, "Output folder")->capture_default_str();
  sub.add_flag("--sweeps", opt.sweeps, "Also run the stability sweeps (slow)");
  // A strain RMS error: 1 (100 % strain) already means any result passes.
  sub.add_option("--max-rms", opt.limits.max_rms, "Sweep failure: strain RMS error above this")
      ->check(within(1e-6, 1.0))
      ->capture_default_str();
  sub.add_option("--min-points", opt.limits.min_points,
                 "Sweep failure: median tracked landmarks per frame below this")
      ->check(within(0.0, 1000000.0))
      ->capture_default_str();
}

}  // namespace tactile::cli
