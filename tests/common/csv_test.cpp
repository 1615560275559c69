#include "tactile/common/csv.hpp"
#include "../common/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

TEST(Csv, WritesHeaderThenRows) {
  const tactile::test::TempDir dir;
  const fs::path p = dir / "t.csv";
  auto out = tactile::csv::open_with_header(p, "a,b");
  out << "1,2\n";
  tactile::csv::finish(out, p);
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "a,b\n1,2\n");
}

TEST(Csv, UnwritablePathIsNamed) {
  try {
    tactile::csv::open_with_header("/nonexistent-dir/x.csv", "a");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.csv"), std::string::npos);
  }
}
