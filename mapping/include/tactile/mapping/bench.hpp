#pragma once
// The mapping benchmark (`tactile bench map`): how long mapping a demo-sized strain movie onto a
// layout takes for every strain mode and method, and the table that reports it. The command
// line only chooses the sizes and prints; the movie, the timing and the table are made here.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// The scene's exact strain on a landmark grid of `spacing_mm`, Delaunay-triangulated with an
// edge list as a measured movie comes, so that the mapping does the work it does on one.
capture::StrainMovie bench_strain_movie(const capture::SceneSpec& spec, double spacing_mm);

// "bench map: N strain frames, L landmarks and T triangles per frame on average -> LAYOUT RxC
// at 700 Hz; H hardware threads" (landmarks averaged over the frames, triangles of the first).
std::string map_bench_heading(const capture::StrainMovie& movie, const movie::Layout& layout,
                              unsigned hardware_threads);

struct MapBenchRow {
  MappingMethod method = MappingMethod::proportional;
  StrainMode strain = StrainMode::per_frame;
  std::int32_t frames = 0;  // of the mapped movie
  double median_ms = 0, min_ms = 0, max_ms = 0;
  // CPU time of the whole process (all worker threads): what the mapping costs when other
  // programs share the cores and wall time says more about them than about us.
  double median_cpu_ms = 0;
};

// Every strain mode x method (kStrainModes, kMappingMethods), each mapped `repeats` times onto
// `layout` with default parameters (the profile method given the scene's profile); on_row sees
// each row as soon as it is timed.
std::vector<MapBenchRow> bench_mapping(const capture::StrainMovie& movie,
                                       const capture::SceneSpec& spec, const movie::Layout& layout,
                                       int repeats,
                                       const std::function<void(const MapBenchRow&)>& on_row);

// The table's column names and one line per row, newline-terminated.
std::string map_bench_table_header();
std::string map_bench_table_row(const MapBenchRow& row);

}  // namespace tactile::mapping
