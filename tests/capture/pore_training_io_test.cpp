#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/common/error.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// A 20 x 10 px grey image: marks must lie in rows 1..10, cols 1..20.
void write_image(const fs::path& path) {
  write_png(path, GrayImage{20, 10, std::vector<std::uint8_t>(200, 128)});
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The FormatError message of reading `dir`, or "" when it was read.
std::string read_error(const fs::path& dir) {
  try {
    read_pore_training_prints(dir);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const fs::path& dir, const std::vector<std::string>& parts) {
  const std::string message = read_error(dir);
  ASSERT_FALSE(message.empty()) << "read without error";
  for (const auto& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

TEST(PoreTrainingIo, ReadsPairsInNumericOrderAsZeroBasedXY) {
  TempDir dir;
  write_image(dir.path() / "image_10.png");
  write_text(dir.path() / "pores_10.txt", "1 1\n10 20\n");
  // BMP, upper-case extension, tabs, CRLF line ends and blank lines are all accepted.
  write_image(dir.path() / "image_2.BMP");
  write_text(dir.path() / "pores_2.txt", "3\t5\r\n\r\n  7.5  2 \r\n\n");
  write_text(dir.path() / "notes.txt", "not a marks file");
  const auto prints = read_pore_training_prints(dir.path());
  ASSERT_EQ(prints.size(), 2u);
  EXPECT_EQ(prints[0].name, "image_2.BMP");  // 2 before 10
  EXPECT_EQ(prints[1].name, "image_10.png");
  EXPECT_EQ(prints[0].image.width_px, 20);
  EXPECT_EQ(prints[0].image.height_px, 10);
  ASSERT_EQ(prints[0].pores_px.size(), 2u);
  // `row col`, 1-based -> x = col - 1, y = row - 1.
  EXPECT_DOUBLE_EQ(prints[0].pores_px[0][0], 4.0);
  EXPECT_DOUBLE_EQ(prints[0].pores_px[0][1], 2.0);
  EXPECT_DOUBLE_EQ(prints[0].pores_px[1][0], 1.0);
  EXPECT_DOUBLE_EQ(prints[0].pores_px[1][1], 6.5);
  ASSERT_EQ(prints[1].pores_px.size(), 2u);
  EXPECT_DOUBLE_EQ(prints[1].pores_px[1][0], 19.0);
  EXPECT_DOUBLE_EQ(prints[1].pores_px[1][1], 9.0);
}

TEST(PoreTrainingIo, ListsTheFilesItWouldReadWithoutReadingThem) {
  TempDir dir;
  write_text(dir.path() / "image_1.png", "not decoded when listing");
  write_text(dir.path() / "pores_1.txt", "1 1\n");
  write_text(dir.path() / "pores_2.txt", "1 1\n");  // no image: listed all the same
  write_text(dir.path() / "notes.txt", "not a marks file");
  EXPECT_EQ(pore_training_files(dir.path()),
            (std::vector<fs::path>{dir.path() / "image_1.png", dir.path() / "pores_1.txt",
                                   dir.path() / "pores_2.txt"}));
  EXPECT_TRUE(pore_training_files(dir.path() / "nowhere").empty());
}

TEST(PoreTrainingIo, MissingOrEmptyDirectory) {
  TempDir dir;
  expect_error(dir.path() / "nowhere", {"nowhere", "no such directory"});
  expect_error(dir.path(), {dir.path().string(), "no marked prints", "pores_NN.txt"});
  write_text(dir.path() / "readme.txt", "x");
  write_image(dir.path() / "photo.png");
  expect_error(dir.path(), {"no marked prints"});
}

TEST(PoreTrainingIo, ImageWithoutMarksAndMarksWithoutImage) {
  TempDir a;
  write_image(a.path() / "image_01.png");
  write_text(a.path() / "pores_01.txt", "1 1\n");
  write_image(a.path() / "image_03.png");
  expect_error(a.path(), {"image_03.png", "without its marks file pores_03.txt"});
  TempDir b;
  write_text(b.path() / "pores_07.txt", "1 1\n");
  expect_error(b.path(), {"pores_07.txt", "without their image image_07."});
}

TEST(PoreTrainingIo, TwoImagesForOnePrint) {
  TempDir dir;
  write_image(dir.path() / "image_01.png");
  write_image(dir.path() / "image_01.jpg");
  write_text(dir.path() / "pores_01.txt", "1 1\n");
  expect_error(dir.path(), {"two files for print 01"});
}

// Each bad marks file against a good image: the message names the file and the line.
TEST(PoreTrainingIo, MalformedMarksLines) {
  struct Case {
    std::string text;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {"1 1\n2 x\n", {"pores_01.txt:2", "expected two numbers", "'x'"}},
      {"1 1\n\n4\n", {"pores_01.txt:3", "found only '4'"}},
      {"1,2\n", {"pores_01.txt:1", "'1,2'"}},
      {"1 1\n2 2 3\n", {"pores_01.txt:2", "extra columns", "3 fields"}},
      {"5 nan\n", {"pores_01.txt:1", "expected two numbers", "'nan'"}},
      {"11 3\n", {"pores_01.txt:1", "row 11 col 3", "outside the 20 x 10 px image"}},
      {"3 21\n", {"pores_01.txt:1", "outside"}},
      {"0 5\n", {"pores_01.txt:1", "outside"}},
      {"", {"pores_01.txt", "no marks"}},
      {"\n  \n", {"pores_01.txt", "no marks"}},
  };
  for (const auto& c : cases) {
    TempDir dir;
    write_image(dir.path() / "image_01.png");
    write_text(dir.path() / "pores_01.txt", c.text);
    SCOPED_TRACE("marks: '" + c.text + "'");
    expect_error(dir.path(), c.parts);
  }
}

TEST(PoreTrainingIo, UnreadableImage) {
  TempDir dir;
  write_text(dir.path() / "image_01.jpg", "not a jpeg at all");
  write_text(dir.path() / "pores_01.txt", "1 1\n");
  expect_error(dir.path(), {"image_01.jpg", "not a readable image"});
}

}  // namespace
}  // namespace tactile::capture
