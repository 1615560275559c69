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

TEST(Csv, LineReaderTakesCrLfAndByteOrderMark) {
  std::istringstream in(
      "\xEF\xBB\xBF"
      "a,b\r\n1,2\r\n\r\n3,4\n");
  tactile::csv::LineReader lines(in);
  std::string line;
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "a,b");
  EXPECT_EQ(lines.number(), 1U);
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "1,2");
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line, "3,4");
  EXPECT_EQ(lines.number(), 4U);
  EXPECT_FALSE(lines.next(line));
}

TEST(Csv, LineReaderKeepsAByteOrderMarkAfterTheFirstLine) {
  // Only a file's first bytes can be its byte-order mark; later it is part of a field.
  std::istringstream in(
      "a\n\xEF\xBB\xBF"
      "b\n");
  tactile::csv::LineReader lines(in);
  std::string line;
  ASSERT_TRUE(lines.next(line));
  ASSERT_TRUE(lines.next(line));
  EXPECT_EQ(line,
            "\xEF\xBB\xBF"
            "b");
}
