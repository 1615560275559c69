#include "tactile/common/output_paths.hpp"
#include "../common/temp_dir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using tactile::output_file;
using tactile::output_folder;
using tactile::OutputIsInputError;
using tactile::refuse_output_over_input;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

class OutputPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "in");
    std::ofstream(dir_ / "in" / "s.h5") << "strain";
    std::ofstream(dir_ / "in" / "frame_000.png") << "image";
  }

  // The refusal's message, or "" when the paths are accepted.
  static std::string refusal(const std::vector<tactile::Output>& outputs,
                             const std::vector<tactile::NamedPath>& inputs) {
    try {
      refuse_output_over_input(outputs, inputs);
      return "";
    } catch (const OutputIsInputError& e) {
      return e.what();
    }
  }

  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

TEST_F(OutputPathsTest, SamePathIsRefusedNamingBothOptionsAndPaths) {
  const auto s = dir_ / "in" / "s.h5";
  const std::string m = refusal({output_file("--out", s)}, {{"STRAIN_H5", s}});
  EXPECT_THAT(m, HasSubstr("--out " + s.string()));
  EXPECT_THAT(m, HasSubstr("input STRAIN_H5 " + s.string()));
  EXPECT_THAT(m, Not(HasSubstr("link")));
}

TEST_F(OutputPathsTest, OtherSpellingOfThePathIsTheSameFile) {
  const auto s = dir_ / "in" / "s.h5";
  EXPECT_THAT(
      refusal({output_file("--out", dir_ / "in" / "." / ".." / "in" / "s.h5")}, {{"STRAIN_H5", s}}),
      HasSubstr("would write over the input"));
}

TEST_F(OutputPathsTest, SymbolicLinkToTheInputIsRefused) {
  fs::create_symlink(dir_ / "in" / "s.h5", dir_ / "link.h5");
  EXPECT_THAT(refusal({output_file("--out", dir_ / "link.h5")}, {{"STRAIN_H5", dir_ / "in/s.h5"}}),
              HasSubstr("through a symbolic link"));
  // A symbolic link to the input's folder, too.
  fs::create_directory_symlink(dir_ / "in", dir_ / "in-link");
  EXPECT_THAT(
      refusal({output_file("--out", dir_ / "in-link" / "s.h5")}, {{"STRAIN_H5", dir_ / "in/s.h5"}}),
      HasSubstr("through a symbolic link"));
}

TEST_F(OutputPathsTest, HardLinkToTheInputIsRefused) {
  fs::create_hard_link(dir_ / "in" / "s.h5", dir_ / "hard.h5");
  EXPECT_THAT(refusal({output_file("--out", dir_ / "hard.h5")}, {{"STRAIN_H5", dir_ / "in/s.h5"}}),
              HasSubstr("through a hard link"));
}

TEST_F(OutputPathsTest, NewFileBesideTheInputIsAccepted) {
  EXPECT_EQ(refusal({output_file("--out", dir_ / "in" / "movie.h5"),
                     output_file("--csv", dir_ / "in" / "movie.csv")},
                    {{"STRAIN_H5", dir_ / "in" / "s.h5"}}),
            "");
  // An existing output that is not an input may be replaced.
  std::ofstream(dir_ / "in" / "movie.h5") << "old movie";
  EXPECT_EQ(refusal({output_file("--out", dir_ / "in" / "movie.h5")},
                    {{"STRAIN_H5", dir_ / "in" / "s.h5"}}),
            "");
}

TEST_F(OutputPathsTest, OutputFileOnAnInputFolderIsRefused) {
  EXPECT_THAT(refusal({output_file("--out", dir_ / "in")}, {{"IMAGE_DIR", dir_ / "in"}}),
              HasSubstr("input IMAGE_DIR"));
}

TEST_F(OutputPathsTest, FolderOutputIsRefusedOnlyForTheNamesItWrites) {
  const std::vector<tactile::NamedPath> inputs = {{"IMAGE_DIR", dir_ / "in"},
                                                  {"IMAGE_DIR", dir_ / "in" / "frame_000.png"}};
  // The input's own folder, writing other names: accepted.
  EXPECT_EQ(refusal({output_folder("--csv", dir_ / "in", {"tracks.csv", "edges.csv"})}, inputs),
            "");
  // Writing a name that is an input: refused, naming the file.
  const std::string m = refusal({output_folder("--maps", dir_ / "in", {"frame_000.png"})}, inputs);
  EXPECT_THAT(m, HasSubstr("--maps " + (dir_ / "in").string() + " (its frame_000.png)"));
  EXPECT_THAT(m, HasSubstr("input IMAGE_DIR " + (dir_ / "in" / "frame_000.png").string()));
}

TEST_F(OutputPathsTest, FolderOutputOnAnInputFileIsRefused) {
  const auto s = dir_ / "in" / "s.h5";
  EXPECT_THAT(
      refusal({output_folder("--csv", s, {"tracks.csv"})}, {{"STRAIN", s}}),
      HasSubstr("--csv " + s.string() + " would write over the input STRAIN " + s.string()));
}

TEST_F(OutputPathsTest, EveryFileOfAWrittenSubfolderCountsAsOverwritten) {
  fs::create_directories(dir_ / "out" / "movies");
  fs::create_hard_link(dir_ / "in" / "s.h5", dir_ / "out" / "movies" / "run.h5");
  const std::string m = refusal({output_folder("--out", dir_ / "out", {"metrics.csv"}, {"movies"})},
                                {{"sources[0].file", dir_ / "in" / "s.h5"}});
  EXPECT_THAT(m, HasSubstr("(its movies/run.h5)"));
  EXPECT_THAT(m, HasSubstr("hard link"));
  // A sub-folder that is not written may hold inputs.
  EXPECT_EQ(refusal({output_folder("--out", dir_ / "out", {"metrics.csv"}, {"plots"})},
                    {{"sources[0].file", dir_ / "out" / "movies" / "run.h5"}}),
            "");
}

TEST_F(OutputPathsTest, TwoOutputsOnOneFileAreRefused) {
  const std::string m = refusal(
      {output_file("--out", dir_ / "movie.h5"), output_file("--csv", dir_ / "movie.h5")}, {});
  EXPECT_THAT(m, HasSubstr("--out " + (dir_ / "movie.h5").string()));
  EXPECT_THAT(m, HasSubstr("--csv " + (dir_ / "movie.h5").string()));
  EXPECT_THAT(m, HasSubstr("the same file"));
}

TEST_F(OutputPathsTest, SameFileFollowsLinksAndSpellings) {
  fs::create_hard_link(dir_ / "in" / "s.h5", dir_ / "hard.h5");
  EXPECT_TRUE(tactile::same_file(dir_ / "in" / "s.h5", dir_ / "hard.h5"));
  EXPECT_TRUE(tactile::same_file(dir_ / "nothing" / ".." / "x", dir_ / "x"));
  EXPECT_FALSE(tactile::same_file(dir_ / "in" / "s.h5", dir_ / "in" / "frame_000.png"));
  EXPECT_FALSE(tactile::same_file(dir_ / "in" / "s.h5", dir_ / "in" / "missing.h5"));
}

}  // namespace

namespace {

// The reason an output cannot be written, or "" when it can.
std::string unwritable(const tactile::Output& output) {
  try {
    tactile::refuse_output_over_input({output}, {});
    return "";
  } catch (const tactile::UnwritableOutputError& e) {
    return e.what();
  }
}

TEST_F(OutputPathsTest, AnOutputThatCannotBeWrittenIsFoundBeforeTheWork) {
  const auto missing = dir_ / "missing" / "m.h5";
  EXPECT_THAT(unwritable(output_file("--out", missing)),
              HasSubstr("--out " + missing.string() + ": the folder " +
                        (dir_ / "missing").string() + " does not exist"));
  EXPECT_THAT(unwritable(output_file("--out", dir_ / "in")),
              HasSubstr("--out " + (dir_ / "in").string() + ": is a folder"));
  EXPECT_THAT(unwritable(output_file("--out", dir_ / "in" / "s.h5" / "m.h5")),
              HasSubstr("is not a folder"));
  // Found by the second hostile-input run: `map --out ""` failed in HDF5, `play --preview ""`
  // silently wrote no preview.
  EXPECT_THAT(unwritable(output_file("--out", "")),
              HasSubstr("--out: the path is empty; give a file name"));
  EXPECT_THAT(unwritable(output_folder("--csv", "", {"a.csv"})),
              HasSubstr("--csv: the path is empty; give a folder name"));
  EXPECT_THAT(unwritable(output_file("--preview", "/dev/null")),
              HasSubstr("--preview /dev/null: is not a regular file"));
  EXPECT_THAT(unwritable(output_folder("--csv", dir_ / "in" / "s.h5", {"a.csv"})),
              HasSubstr("--csv " + (dir_ / "in" / "s.h5").string() + ": is a file, not a folder"));
  fs::create_directories(dir_ / "out" / "a.csv");
  EXPECT_THAT(unwritable(output_folder("--csv", dir_ / "out", {"a.csv"})),
              HasSubstr("--csv " + (dir_ / "out").string() + " (its a.csv): is a folder"));
  // A folder created with its parents, under a file: cannot be made.
  EXPECT_THAT(unwritable(output_folder("--csv", dir_ / "in" / "s.h5" / "x" / "y", {"a.csv"})),
              HasSubstr("is not a folder"));
  // Writable ones pass: new file, existing file, new folder (with new parents), existing folder.
  EXPECT_EQ(unwritable(output_file("--out", dir_ / "new.h5")), "");
  EXPECT_EQ(unwritable(output_file("--out", dir_ / "in" / "s.h5")), "");
  EXPECT_EQ(unwritable(output_folder("--csv", dir_ / "n" / "e" / "w", {"a.csv"})), "");
  EXPECT_EQ(unwritable(output_folder("--csv", dir_ / "in", {"a.csv"})), "");
}

}  // namespace
