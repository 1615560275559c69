#include "tactile/mapping/bench.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "tactile/capture/capture.hpp"
#include "tactile/capture/ground_truth.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/mapping/profile.hpp"

namespace tactile::mapping {

capture::StrainMovie bench_strain_movie(const capture::SceneSpec& spec, double spacing_mm) {
  auto movie = capture::ground_truth_strain_movie(spec, spacing_mm);
  for (auto& f : movie.frames) {
    f.edges.clear();
    f.triangles.clear();
    capture::triangulate_strain(f.points_from, f.points_to, 3.0, f.edges, f.triangles);
  }
  return movie;
}

std::string map_bench_heading(const capture::StrainMovie& movie, const movie::Layout& layout,
                              unsigned hardware_threads) {
  std::size_t points = 0;
  for (const auto& f : movie.frames) points += f.points_from.size();
  return fmt::format(
      "bench map: {} strain frames, {:.0f} landmarks and {:.0f} triangles per frame on "
      "average -> {} {}x{} at 700 Hz; {} hardware threads\n",
      movie.frames.size(), static_cast<double>(points) / movie.frames.size(),
      static_cast<double>(movie.frames.front().triangles.size()), layout.name, layout.rows,
      layout.cols, hardware_threads);
}

std::vector<MapBenchRow> bench_mapping(const capture::StrainMovie& movie,
                                       const capture::SceneSpec& spec, const movie::Layout& layout,
                                       int repeats,
                                       const std::function<void(const MapBenchRow&)>& on_row) {
  std::vector<MapBenchRow> rows;
  for (const auto strain : kStrainModes) {
    MappingParams params;
    params.strain = strain;
    const auto source = strain_source(movie, params);
    for (const auto method : kMappingMethods) {
      params.method = method;
      if (method == MappingMethod::profile) params.profile = profile_of_scene(spec);
      MapBenchRow row{.method = method, .strain = strain};
      std::vector<double> ms, cpu_ms;
      for (int r = 0; r < repeats; ++r) {
        const Stopwatch clock;
        row.frames = map_strain_frames(source, layout, params).movie.frame_count;
        cpu_ms.push_back(1e3 * clock.cpu_s());
        ms.push_back(1e3 * clock.wall_s());
      }
      std::sort(ms.begin(), ms.end());
      row.median_ms = median(ms);
      row.min_ms = ms.front();
      row.max_ms = ms.back();
      row.median_cpu_ms = median(cpu_ms);
      rows.push_back(row);
      if (on_row) on_row(row);
    }
  }
  return rows;
}

std::string map_bench_table_header() {
  return fmt::format("{:<14} {:<12} {:>8} {:>10} {:>10} {:>10} {:>12}\n", "method", "strain",
                     "frames", "median ms", "min ms", "max ms", "median cpu ms");
}

std::string map_bench_table_row(const MapBenchRow& row) {
  return fmt::format("{:<14} {:<12} {:>8} {:>10.1f} {:>10.1f} {:>10.1f} {:>12.1f}\n",
                     to_string(row.method), to_string(row.strain), row.frames, row.median_ms,
                     row.min_ms, row.max_ms, row.median_cpu_ms);
}

}  // namespace tactile::mapping
