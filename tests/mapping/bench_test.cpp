// The mapping benchmark's movie, rows and table.

#include "tactile/mapping/bench.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "synthetic.hpp"

namespace tactile::mapping {
namespace {

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

TEST(MapBench, TableRowIsTheHeadersColumns) {
  const MapBenchRow row{.method = MappingMethod::integrated,
                        .strain = StrainMode::accumulated,
                        .frames = 222,
                        .median_ms = 5.24,
                        .min_ms = 4.04,
                        .max_ms = 7.96,
                        .median_cpu_ms = 10.5};
  const std::vector<std::string> header = {"method", "strain", "frames", "median", "ms",  "min",
                                           "ms",     "max",    "ms",     "median", "cpu", "ms"};
  EXPECT_EQ(words(map_bench_table_header()), header);
  // One decimal, as a person reads milliseconds.
  const std::vector<std::string> expected = {"integrated", "accumulated", "222", "5.2",
                                             "4.0",        "8.0",         "10.5"};
  EXPECT_EQ(words(map_bench_table_row(row)), expected);
  EXPECT_EQ(map_bench_table_row(row).back(), '\n');
}

TEST(MapBench, MovieIsTriangulatedLikeAMeasuredOne) {
  capture::SceneSpec spec;
  spec.frame_count = 4;
  const auto movie = bench_strain_movie(spec, 1.0);
  ASSERT_FALSE(movie.frames.empty());
  for (const auto& f : movie.frames) {
    EXPECT_FALSE(f.points_from.empty());
    EXPECT_FALSE(f.triangles.empty());
    EXPECT_FALSE(f.edges.empty());
  }
  const std::string heading = map_bench_heading(movie, testing::grid_layout(3, 4, 1.0, 1.0), 2);
  EXPECT_TRUE(
      heading.starts_with("bench map: " + std::to_string(movie.frames.size()) + " strain frames, "))
      << heading;
  EXPECT_NE(heading.find(" 3x4 "), std::string::npos) << heading;
  EXPECT_NE(heading.find("; 2 hardware threads"), std::string::npos) << heading;
}

TEST(MapBench, EveryStrainModeAndMethodIsTimedInOrder) {
  capture::SceneSpec spec;
  spec.frame_count = 4;
  const auto movie = bench_strain_movie(spec, 1.0);
  std::vector<MapBenchRow> seen;
  const auto rows = bench_mapping(movie, spec, testing::grid_layout(3, 4, 1.0, 1.0), 3,
                                  [&](const MapBenchRow& r) { seen.push_back(r); });
  ASSERT_EQ(rows.size(), kStrainModes.size() * kMappingMethods.size());
  ASSERT_EQ(seen.size(), rows.size());
  std::size_t k = 0;
  for (const auto strain : kStrainModes) {
    for (const auto method : kMappingMethods) {
      const auto& r = rows[k++];
      EXPECT_EQ(r.strain, strain);
      EXPECT_EQ(r.method, method);
      EXPECT_GT(r.frames, 0);
      EXPECT_LE(r.min_ms, r.median_ms);
      EXPECT_LE(r.median_ms, r.max_ms);
      EXPECT_GE(r.median_cpu_ms, 0);
    }
  }
}

}  // namespace
}  // namespace tactile::mapping
