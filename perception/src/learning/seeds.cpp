// Table 2 over several seeds (see seeds.hpp).

#include "tactile/perception/seeds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "tactile/common/csv.hpp"

namespace tactile::perception {

std::vector<std::string> seed_spread_lines(const std::vector<SeedTable2>& runs) {
  std::vector<std::string> lines;
  if (runs.empty()) return lines;
  const auto& first = runs.front().rows;
  const auto other_table = [&](const SeedTable2& run) {
    return std::invalid_argument(
        fmt::format("Table 2 of seed {} has other rows or held-out trials than that of seed {}",
                    run.seed, runs.front().seed));
  };
  for (const SeedTable2& run : runs)
    if (run.rows.size() != first.size()) throw other_table(run);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const CascadeResult& r0 = first[i].result;
    int lowest = r0.correct, highest = r0.correct, sum = 0;
    for (const SeedTable2& run : runs) {
      // A row that differs is another table, and a spread across it would mean nothing.
      if (run.rows[i].result.inputs != r0.inputs || run.rows[i].result.degree != r0.degree ||
          run.rows[i].result.tested != r0.tested)
        throw other_table(run);
      const int c = run.rows[i].result.correct;
      lowest = std::min(lowest, c);
      highest = std::max(highest, c);
      sum += c;
    }
    const std::string range =
        lowest == highest ? fmt::format("{}", lowest) : fmt::format("{}-{}", lowest, highest);
    lines.push_back(fmt::format("{} exp {}: {} of {} correct over {} seed{} (mean {:.1f})",
                                r0.inputs, r0.degree, range, r0.tested, runs.size(),
                                runs.size() == 1 ? "" : "s",
                                static_cast<double>(sum) / static_cast<double>(runs.size())));
  }
  return lines;
}

void write_table2_seeds_csv(const std::filesystem::path& path,
                            const std::vector<SeedTable2>& runs) {
  auto out = csv::open_with_header(path,
                                   "seed,inputs,degree,correct,tested,accuracy,r2_planar,"
                                   "r2_conical,r2_spherical,cascade_rms_mm");
  for (const SeedTable2& run : runs)
    for (const TimedCascade& row : run.rows) {
      const CascadeResult& r = row.result;
      out << fmt::format("{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", run.seed, r.inputs,
                         r.degree, r.correct, r.tested,
                         r.tested ? static_cast<double>(r.correct) / r.tested : 0.0, r.r2[0],
                         r.r2[1], r.r2[2], r.cascade_rms_mm);
    }
  csv::finish(out, path);
}

}  // namespace tactile::perception
