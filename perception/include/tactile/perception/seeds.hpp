#pragma once
// Table 2 repeated over several seeds of the simulated data set. One 90/10 split of 48 features x
// 20 trials holds out only 96 trials, and a feature's held-out trials tend to be right or wrong
// together, so a row moves by up to 6 trials from seed to seed (measured, seeds 1-6); the spread
// says which differences between rows, sensors or settings are more than that.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tactile/perception/report.hpp"

namespace tactile::perception {

struct SeedTable2 {
  std::uint64_t seed = 0;
  std::vector<TimedCascade> rows;  // as run_table2 returns them
};

// One line per Table 2 row (in the first run's order): the held-out curvature accuracy's lowest,
// highest and mean over the runs, e.g. "all exp 1: 79-83 of 96 correct over 6 seeds (mean 81.2)"
// (one number when they agree).
// Every run must have the same rows with the same number of held-out trials
// (std::invalid_argument otherwise).
std::vector<std::string> seed_spread_lines(const std::vector<SeedTable2>& runs);

// CSV `seed,inputs,degree,correct,tested,accuracy,r2_planar,r2_conical,r2_spherical,
// cascade_rms_mm`: every row of every run.
void write_table2_seeds_csv(const std::filesystem::path& path, const std::vector<SeedTable2>& runs);

}  // namespace tactile::perception
