// The one way of writing a file: a random temporary file created exclusively next to the
// destination, renamed over it. Links planted at guessable names are never followed, leftovers
// of earlier runs are never reused, and a failure (full disk, signal) leaves the old file and no
// temporary file; errors name the file and the OS's reason.
#include "tactile/common/atomic_write.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "../common/error_of.hpp"
#include "../common/small_disk.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/h5.hpp"

using tactile::test::error_of;

namespace tactile {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> names_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

class AtomicWrite : public ::testing::Test {
 protected:
  test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

TEST_F(AtomicWrite, ReplacesTheFileAndLeavesNothingElse) {
  const fs::path p = dir_ / "out.txt";
  write_atomically(p, "old\n");
  write_atomically(p, "new\n");
  EXPECT_EQ(bytes(p), "new\n");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"out.txt"});
}

// Every name the writers used before, and the one a guesser would try next.
TEST_F(AtomicWrite, ALinkPlantedAtAGuessableNameIsNotFollowed) {
  const fs::path victim = dir_ / "victim.h5";
  std::ofstream(victim) << "precious";
  for (const char* name : {"out.json.partial", ".out.json.tmp", "out.json.tmp", "out.json~"}) {
    fs::create_symlink(victim, dir_ / name);
  }
  write_text_atomically(dir_ / "out.json", "{}\n");
  EXPECT_EQ(bytes(victim), "precious");
  EXPECT_EQ(bytes(dir_ / "out.json"), "{}\n");
  for (const char* name : {"out.json.partial", ".out.json.tmp", "out.json.tmp", "out.json~"}) {
    EXPECT_TRUE(fs::is_symlink(dir_ / name)) << name;
  }
}

TEST_F(AtomicWrite, ALinkAtTheDestinationIsReplacedNotWrittenThrough) {
  const fs::path victim = dir_ / "victim.csv";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, dir_ / "out.csv");
  write_atomically(dir_ / "out.csv", "a,b\n");
  EXPECT_EQ(bytes(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(dir_ / "out.csv"));
  EXPECT_EQ(bytes(dir_ / "out.csv"), "a,b\n");
}

TEST_F(AtomicWrite, AStalePartialOfAnEarlierRunIsNeitherReadNorReused) {
  std::ofstream(dir_ / "m.h5.partial") << "stale half of an interrupted run";
  write_atomically(dir_ / "m.h5", "whole");
  EXPECT_EQ(bytes(dir_ / "m.h5"), "whole");
  EXPECT_EQ(bytes(dir_ / "m.h5.partial"), "stale half of an interrupted run");
}

TEST_F(AtomicWrite, TwoWritesAtOnceUseTwoTemporaryFiles) {
  AtomicFile a(dir_ / "same.txt");
  AtomicFile b(dir_ / "same.txt");
  EXPECT_NE(a.temporary_path(), b.temporary_path());
  EXPECT_EQ(a.temporary_path().parent_path(), dir_);
  a.write("a");
  b.write("b");
  a.commit();
  b.commit();
  EXPECT_EQ(bytes(dir_ / "same.txt"), "b");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"same.txt"});
}

TEST_F(AtomicWrite, AnAbandonedWriteLeavesTheOldFileAndNoTemporaryFile) {
  const fs::path p = dir_ / "kept.txt";
  write_atomically(p, "old\n");
  {
    AtomicFile f(p);
    f.write("half");
    EXPECT_TRUE(fs::exists(f.temporary_path()));
  }
  {
    AtomicOstream out(p);
    out << "half of a CSV\n";
    out.flush();
  }
  EXPECT_THROW(
      h5::write_file_atomically(p, [](H5::H5File&) { throw std::runtime_error("mapping failed"); }),
      std::runtime_error);
  EXPECT_EQ(bytes(p), "old\n");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"kept.txt"});
}

TEST_F(AtomicWrite, ErrorsNameTheFileAndTheReason) {
  EXPECT_THAT(error_of([&] { write_atomically(dir_ / "no" / "such" / "f.txt", "x"); }),
              HasSubstr((dir_ / "no" / "such" / "f.txt").string() +
                        ": cannot create a file in its folder: No such file or directory"));
  fs::create_directories(dir_ / "folder");
  EXPECT_THAT(error_of([&] { write_atomically(dir_ / "folder", "x"); }),
              HasSubstr((dir_ / "folder").string() + ": Is a directory"));
  // A device is not replaced by a file: /dev/null stays a device.
  EXPECT_THAT(error_of([&] { write_atomically("/dev/null", "x"); }),
              HasSubstr("/dev/null: not a regular file"));
  EXPECT_FALSE(fs::is_regular_file("/dev/null"));
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"folder"});
}

TEST_F(AtomicWrite, AFullDiskKeepsTheOldFileAndSaysSo) {
  const test::SmallDisk disk(64);
  const fs::path p = disk / "out.csv";
  write_atomically(p, "old\n");
  const std::string big(200 * 1024, 'x');
  EXPECT_THAT(error_of([&] { write_atomically(p, big); }),
              HasSubstr("cannot write " + p.string() + ": No space left on device"));
  EXPECT_EQ(bytes(p), "old\n");
  EXPECT_EQ(names_in(disk.path()), std::set<std::string>{"out.csv"});

  // The stream form keeps the first error for commit().
  AtomicOstream out(p);
  for (int i = 0; i < 20000; ++i) out << "1234567890\n";
  EXPECT_THAT(error_of([&] { out.commit(); }), HasSubstr(p.string() + ": No space left on device"));
  EXPECT_EQ(bytes(p), "old\n");
}

// HDF5 builds the file in memory: a full disk is our write's error, not a crash in HDF5's close.
TEST_F(AtomicWrite, AFullDiskUnderAnHdf5FileIsAnErrorNotACrash) {
  const test::SmallDisk disk(64);
  const fs::path p = disk / "movie.h5";
  write_atomically(p, "old movie");
  disk.fill();
  std::vector<double> noise(50000);
  for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<double>(i * 7919 % 10007);
  EXPECT_THAT(error_of([&] {
                h5::write_file_atomically(
                    p, [&](H5::H5File& f) { h5::write_dataset(f, "d", noise, {noise.size()}); });
              }),
              HasSubstr("cannot write " + p.string() + ": No space left on device"));
  EXPECT_EQ(bytes(p), "old movie");
  EXPECT_EQ(names_in(disk.path()), (std::set<std::string>{"filler", "movie.h5"}));
}

// A child writes without end; SIGTERM or SIGINT while its temporary file exists removes the file
// and ends the child by that signal (a shell's 143 or 130), the old file as it was.
void expect_signal_cleans_up(const fs::path& dir, int sig) {
  const fs::path p = dir / "movie.h5";
  write_atomically(p, "old movie");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    AtomicOstream out(p);
    const std::string block(4096, 'm');
    for (;;) {
      out << block;
      out.flush();
      ::usleep(1000);
    }
  }
  bool seen = false;
  for (int i = 0; i < 5000 && !seen; ++i) {
    seen = names_in(dir).size() > 1;
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(seen) << "the child never created its temporary file";
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(child, sig);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(128 + WTERMSIG(status), sig == SIGTERM ? 143 : 130);
  EXPECT_EQ(bytes(p), "old movie");
  EXPECT_EQ(names_in(dir), std::set<std::string>{"movie.h5"});
}

TEST_F(AtomicWrite, SigtermDuringAWriteRemovesTheTemporaryFile) {
  expect_signal_cleans_up(dir_, SIGTERM);
}

TEST_F(AtomicWrite, SigintDuringAWriteRemovesTheTemporaryFile) {
  expect_signal_cleans_up(dir_, SIGINT);
}

TEST_F(AtomicWrite, OutputsCommittedTogetherAppearOnlyAtTheEnd) {
  write_atomically(dir_ / "a.h5", "old a");
  write_atomically(dir_ / "b.csv", "old b");
  {
    CommitTogether together;
    write_atomically(dir_ / "a.h5", "new a");
    EXPECT_EQ(bytes(dir_ / "a.h5"), "old a") << "replaced before the end";
    AtomicOstream csv(dir_ / "b.csv");
    csv << "new b";
    csv.commit();
    write_atomically(dir_ / "c.json", "new c");
    EXPECT_FALSE(fs::exists(dir_ / "c.json"));
    EXPECT_EQ(names_in(dir_).size(), 5u) << "three temporary files beside the two old ones";
    together.commit();
    // After the end, each write is its own commit again.
    write_atomically(dir_ / "d.txt", "d");
    EXPECT_EQ(bytes(dir_ / "d.txt"), "d");
  }
  EXPECT_EQ(bytes(dir_ / "a.h5"), "new a");
  EXPECT_EQ(bytes(dir_ / "b.csv"), "new b");
  EXPECT_EQ(bytes(dir_ / "c.json"), "new c");
  EXPECT_EQ(names_in(dir_), (std::set<std::string>{"a.h5", "b.csv", "c.json", "d.txt"}));
}

TEST_F(AtomicWrite, OutputsOfAFailedRunAreNeitherCommittedNorLeftBehind) {
  write_atomically(dir_ / "a.h5", "old a");
  {
    CommitTogether together;
    write_atomically(dir_ / "a.h5", "new a");
    write_atomically(dir_ / "b.csv", "new b");
    EXPECT_THROW(CommitTogether(), std::logic_error) << "one at a time";
    // Destroyed without commit(): the run failed.
  }
  EXPECT_EQ(bytes(dir_ / "a.h5"), "old a");
  EXPECT_EQ(names_in(dir_), std::set<std::string>{"a.h5"});
}

// A signal after the first output is complete, while the second is being written: neither
// replaces the old one and no temporary file is left.
TEST_F(AtomicWrite, SigtermBetweenOutputsCommittedTogetherReplacesNone) {
  write_atomically(dir_ / "a.h5", "old a");
  write_atomically(dir_ / "b.csv", "old b");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    CommitTogether together;
    write_atomically(dir_ / "a.h5", "new a");
    AtomicOstream csv(dir_ / "b.csv");
    for (;;) {
      csv << "new b\n";
      csv.flush();
      ::usleep(1000);
    }
  }
  bool seen = false;
  for (int i = 0; i < 5000 && !seen; ++i) {
    seen = names_in(dir_).size() == 4;  // both temporary files
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(seen) << "the child never wrote both temporary files";
  ::kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(bytes(dir_ / "a.h5"), "old a");
  EXPECT_EQ(bytes(dir_ / "b.csv"), "old b");
  EXPECT_EQ(names_in(dir_), (std::set<std::string>{"a.h5", "b.csv"}));
}

}  // namespace
}  // namespace tactile
