#pragma once
// Where a stability sweep first fails, for `bench capture --sweeps` and `bench prints --sweeps`:
// accuracy and yield fail at different points, and each is reported on its own.

#include <fmt/format.h>

#include <string>

namespace tactile::cli {

struct SweepFailures {
  double accuracy_at = -1;  // first value whose strain error was too large; -1 = none yet
  double yield_at = -1;     // first value with too few tracked landmarks; -1 = none yet

  void note(double value, bool accurate, bool enough) {
    if (!accurate && accuracy_at < 0) accuracy_at = value;
    if (!enough && yield_at < 0) yield_at = value;
  }
  bool both_failed() const { return accuracy_at >= 0 && yield_at >= 0; }

  // "  -> NAME: strain error fails at V; landmark yield holds up to LAST"
  std::string summary(const std::string& name, double last_value) const {
    auto where = [&](double v) {
      return v >= 0 ? fmt::format("fails at {}", v) : fmt::format("holds up to {}", last_value);
    };
    return fmt::format("  -> {}: strain error {}; landmark yield {}\n", name, where(accuracy_at),
                       where(yield_at));
  }
};

}  // namespace tactile::cli
