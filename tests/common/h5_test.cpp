#include "tactile/common/h5.hpp"
#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using tactile::test::error_of;

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

class H5Test : public ::testing::Test {
 protected:
  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

void write_sample(const fs::path& path) {
  tactile::h5::write_file_atomically(path, [](H5::H5File& f) {
    tactile::h5::write_attr(f, "rate_hz", 700.0);
    tactile::h5::write_attr(f, "count", std::int64_t{42});
    tactile::h5::write_attr(f, "name", "stress");
    tactile::h5::write_dataset(f, "values", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3});
    tactile::h5::write_dataset(f, "ids", std::vector<std::int32_t>{7, 8}, {2});
  });
}

}  // namespace

// A dataset whose data were never written stores nothing: HDF5 would give its fill value for
// every declared value, after the reader allocated them all. A damaged file declaring more values
// than it holds is refused the same way, before the allocation.
TEST_F(H5Test, DatasetDeclaringMoreThanTheFileStoresIsNamedBeforeAllocating) {
  const fs::path p = dir_ / "unwritten.h5";
  {
    H5::H5File f(p.string(), H5F_ACC_TRUNC);
    const hsize_t dims[1] = {50000000};
    const hsize_t chunk[1] = {65536};
    H5::DSetCreatPropList props;
    props.setChunk(1, chunk);
    props.setDeflate(4);
    f.createDataSet("values", H5::PredType::NATIVE_INT32, H5::DataSpace(1, dims), props);
  }
  H5::H5File f = tactile::h5::open_for_reading(p);
  std::vector<hsize_t> dims;
  EXPECT_THAT(error_of<tactile::FormatError>(
                  [&] { tactile::h5::read_ints(f, "values", 1, dims, "unwritten.h5"); }),
              HasSubstr("unwritten.h5/values: declares 50000000 values of 4 bytes each (200000000 "
                        "bytes) but the file stores 0 bytes of them"));
}

TEST_F(H5Test, AttributesAndDatasetsRoundTrip) {
  const fs::path p = dir_ / "a.h5";
  write_sample(p);
  H5::H5File f = tactile::h5::open_for_reading(p);
  EXPECT_DOUBLE_EQ(tactile::h5::read_attr_double(f, "rate_hz", "a"), 700.0);
  EXPECT_EQ(tactile::h5::read_attr_int(f, "count", "a"), 42);
  EXPECT_EQ(tactile::h5::read_attr_string(f, "name", "a"), "stress");
  std::vector<hsize_t> dims;
  EXPECT_EQ(tactile::h5::read_doubles(f, "values", 2, dims, "a"),
            (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(tactile::h5::read_ints(f, "ids", 1, dims, "a"), (std::vector<std::int32_t>{7, 8}));
}

TEST_F(H5Test, MissingEmptyAndNonHdf5FilesAreNamed) {
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::open_for_reading(dir_ / "nope.h5"); }),
      HasSubstr("no such file"));
  std::ofstream(dir_ / "empty.h5").close();
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::open_for_reading(dir_ / "empty.h5"); }),
      HasSubstr("empty"));
  std::ofstream(dir_ / "text.h5") << "frame,t_s\n0,0\n";
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::open_for_reading(dir_ / "text.h5"); }),
      HasSubstr("not an HDF5 file"));
}

TEST_F(H5Test, TruncatedFileIsAClearError) {
  const fs::path p = dir_ / "t.h5";
  write_sample(p);
  fs::resize_file(p, fs::file_size(p) / 2);
  const std::string msg = error_of<tactile::FormatError>([&] {
    H5::H5File f = tactile::h5::open_for_reading(p);
    std::vector<hsize_t> dims;
    tactile::h5::read_doubles(f, "values", 2, dims, "t");
  });
  EXPECT_THAT(msg, HasSubstr("t"));
  EXPECT_NE(msg, "(no error)");
}

TEST_F(H5Test, WrongTypeRankAndMissingObjectsAreNamed) {
  const fs::path p = dir_ / "w.h5";
  write_sample(p);
  H5::H5File f = tactile::h5::open_for_reading(p);
  std::vector<hsize_t> dims;
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_ints(f, "values", 2, dims, "w"); }),
      HasSubstr("expected integer"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_doubles(f, "values", 3, dims, "w"); }),
      HasSubstr("expected 3 dimension(s), found 2"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_doubles(f, "absent", 1, dims, "w"); }),
      HasSubstr("w/absent: dataset is missing"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_attr_string(f, "rate_hz", "w"); }),
      HasSubstr("'rate_hz' must be a string"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_attr_int(f, "rate_hz", "w"); }),
      HasSubstr("must be an integer"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_attr_double(f, "name", "w"); }),
      HasSubstr("must be a number"));
  EXPECT_THAT(
      error_of<tactile::FormatError>([&] { tactile::h5::read_attr_double(f, "absent", "w"); }),
      HasSubstr("'absent' is missing"));
  EXPECT_THAT(error_of<tactile::FormatError>([&] { tactile::h5::open_group(f, "values", "w"); }),
              HasSubstr("not a group"));
}

TEST_F(H5Test, FailedWriteKeepsTheExistingFile) {
  const fs::path p = dir_ / "keep.h5";
  write_sample(p);
  const auto size_before = fs::file_size(p);
  EXPECT_THROW(tactile::h5::write_file_atomically(
                   p, [](H5::H5File&) { throw std::runtime_error("mapping failed"); }),
               std::runtime_error);
  ASSERT_TRUE(fs::exists(p));
  EXPECT_EQ(fs::file_size(p), size_before);
  EXPECT_FALSE(fs::exists(dir_ / "keep.h5.partial"));
  H5::H5File f = tactile::h5::open_for_reading(p);
  EXPECT_EQ(tactile::h5::read_attr_int(f, "count", "keep"), 42);
}

TEST_F(H5Test, LargeDatasetsAreCompressedAndExact) {
  std::vector<float> big(100 * 2100);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<float>(i % 97) * 0.5f;
  const fs::path p = dir_ / "big.h5";
  tactile::h5::write_file_atomically(p, [&](H5::H5File& f) {
    tactile::h5::write_dataset(f, "d", big, {2100, 10, 10});
  });
  EXPECT_LT(fs::file_size(p), big.size() * sizeof(float));
  H5::H5File f = tactile::h5::open_for_reading(p);
  std::vector<hsize_t> dims;
  EXPECT_EQ(tactile::h5::read_floats(f, "d", 3, dims, "big"), big);
}

// Strings are stored fixed-length: reading them never goes through HDF5's global heap, whose
// code crashes on damaged files. The empty string still round-trips.
TEST_F(H5Test, StringsAreWrittenFixedLengthAndRoundTrip) {
  const fs::path p = dir_ / "s.h5";
  tactile::h5::write_file_atomically(p, [](H5::H5File& f) {
    tactile::h5::write_attr(f, "name", "stress2");
    tactile::h5::write_attr(f, "empty", "");
  });
  H5::H5File f = tactile::h5::open_for_reading(p);
  const H5::StrType type = f.openAttribute("name").getStrType();
  EXPECT_FALSE(type.isVariableStr());
  EXPECT_EQ(type.getSize(), 7U);
  EXPECT_EQ(tactile::h5::read_attr_string(f, "name", "s"), "stress2");
  EXPECT_EQ(tactile::h5::read_attr_string(f, "empty", "s"), "");
}

// Files written before strings were fixed-length hold variable-length ones: still readable.
TEST_F(H5Test, VariableLengthStringsOfOlderFilesAreRead) {
  const fs::path p = dir_ / "old.h5";
  {
    H5::H5File f(p.string(), H5F_ACC_TRUNC);
    H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
    type.setCset(H5T_CSET_UTF8);
    f.createAttribute("name", type, H5::DataSpace()).write(type, std::string("latero"));
  }
  H5::H5File f = tactile::h5::open_for_reading(p);
  ASSERT_TRUE(f.openAttribute("name").getStrType().isVariableStr());
  EXPECT_EQ(tactile::h5::read_attr_string(f, "name", "old"), "latero");
}

// A read that kills its process (as HDF5 does on some damaged files) is a FormatError naming the
// file and saying it is damaged; a read that returns or throws lets the caller go on.
TEST_F(H5Test, ReadThatCrashesInTheChildIsADamagedFileError) {
  const fs::path p = dir_ / "d.h5";
  write_sample(p);
  for (const int sig : {SIGSEGV, SIGABRT, SIGBUS}) {
    const std::string msg = error_of(
        [&] { tactile::h5::read_in_child_first(p, "a test file", [sig] { std::raise(sig); }); });
    EXPECT_THAT(msg, HasSubstr("d.h5: damaged file: reading it as a test file crashed"));
    EXPECT_THAT(msg, HasSubstr(fmt::format("signal {}", sig)));
  }
  EXPECT_THAT(
      error_of([&] { tactile::h5::read_in_child_first(p, "a test file", [] { std::_Exit(3); }); }),
      HasSubstr("exit status 3"));
  EXPECT_NO_THROW(tactile::h5::read_in_child_first(p, "a test file", [] {}));
  EXPECT_NO_THROW(tactile::h5::read_in_child_first(
      p, "a test file", [] { throw tactile::FormatError("refused in the child"); }));
}

// A stand-in for a reader (a plain function, as the reading child takes) and for HDF5 on damaged
// files: it writes the process that ran it into the file it is given, and crashes, exits, hangs
// or refuses on the files named so.
void stand_in_reader(const fs::path& p) {
  if (p.filename() == "crash.txt") std::raise(SIGSEGV);
  if (p.filename() == "exit.txt") std::_Exit(4);
  if (p.filename() == "hang.txt") {
    for (;;) ::pause();
  }
  if (p.filename() == "refuse.txt") throw tactile::FormatError("refused in the child");
  std::ofstream(p, std::ios::app) << ::getpid() << '\n';
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// One child reads many files: a fuzzer's thousands of inputs cost one fork, not one each.
TEST_F(H5Test, AReadingProcessServesManyFilesFromOneChild) {
  tactile::h5::ReadingProcess process;
  const fs::path notes = dir_ / "notes.txt";
  for (int i = 0; i < 50; ++i) process.read(notes, "a test file", &stand_in_reader);
  EXPECT_NO_THROW(process.read(dir_ / "refuse.txt", "a test file", &stand_in_reader));
  process.read(notes, "a test file", &stand_in_reader);
  EXPECT_EQ(process.forks(), 1);
  const auto pids = lines_of(notes);
  ASSERT_EQ(pids.size(), 51u);
  for (const auto& pid : pids) EXPECT_EQ(pid, pids.front());
  EXPECT_NE(pids.front(), std::to_string(::getpid()));
}

// A file that kills the child is reported as read_in_child_first reports it; the next file is
// read by a new child.
TEST_F(H5Test, AReadingProcessThatDiesReportsTheFileAndGoesOn) {
  tactile::h5::ReadingProcess process;
  const fs::path notes = dir_ / "notes.txt";
  process.read(notes, "a test file", &stand_in_reader);
  EXPECT_THAT(error_of([&] { process.read(dir_ / "crash.txt", "a test file", &stand_in_reader); }),
              HasSubstr("crash.txt: damaged file: reading it as a test file crashed the HDF5 "
                        "library (signal 11"));
  EXPECT_THAT(error_of([&] { process.read(dir_ / "exit.txt", "a test file", &stand_in_reader); }),
              HasSubstr("exit status 4"));
  process.read(notes, "a test file", &stand_in_reader);
  EXPECT_EQ(process.forks(), 3);
  EXPECT_EQ(lines_of(notes).size(), 2u);
}

// A file that the child never finishes is a damaged file after the bound (10 s for a small
// file), the child killed.
TEST_F(H5Test, AReadingProcessStuckInAFileIsStopped) {
  tactile::h5::ReadingProcess process;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_THAT(error_of([&] { process.read(dir_ / "hang.txt", "a test file", &stand_in_reader); }),
              HasSubstr("hang.txt: damaged file: reading it as a test file did not finish "
                        "within 10 s"));
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(30));
  process.read(dir_ / "notes.txt", "a test file", &stand_in_reader);
  EXPECT_EQ(process.forks(), 2);
}
