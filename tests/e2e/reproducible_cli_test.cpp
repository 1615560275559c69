// The same frames captured twice give the same files: tracks and edges byte for byte, in the
// same order, whatever the threads and the heap did in between.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/strain_movie_io.hpp"

namespace {

namespace fs = std::filesystem;
using tactile::test::run_tactile;

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

TEST(ReproducibleCli, CapturingTheSameFramesTwiceWritesTheSameTracksAndEdgesInTheSameOrder) {
  const tactile::test::TempDir dir;
  const fs::path seq = dir.path() / "seq";
  auto r = run_tactile("synth " + seq.string() + " --frames 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* run : {"1", "2"}) {
    r = run_tactile("capture " + seq.string() + " --px-per-mm 20 --min-track 10 --out " +
                    (dir.path() / (std::string("m") + run + ".h5")).string() + " --csv " +
                    (dir.path() / (std::string("c") + run)).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  for (const char* file : {"tracks.csv", "edges.csv"}) {
    const std::string first = contents(dir.path() / "c1" / file);
    ASSERT_GT(first.size(), 1000u) << file;
    EXPECT_TRUE(first == contents(dir.path() / "c2" / file)) << file << " differs between runs";
  }
  const auto a = tactile::capture::read_strain_movie(dir.path() / "m1.h5");
  const auto b = tactile::capture::read_strain_movie(dir.path() / "m2.h5");
  ASSERT_EQ(a.frames.size(), b.frames.size());
  ASSERT_GT(a.frames.size(), 10u);
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    const auto &ea = a.frames[f].edges, &eb = b.frames[f].edges;
    ASSERT_EQ(ea.size(), eb.size()) << "frame " << f;
    int moved = 0;
    for (std::size_t i = 0; i < ea.size(); ++i) {
      moved += ea[i].track_a != eb[i].track_a || ea[i].track_b != eb[i].track_b ||
               ea[i].rel_change != eb[i].rel_change;
    }
    EXPECT_EQ(moved, 0) << "frame " << f << ": edges in another order or with another strain";
  }
}

}  // namespace
