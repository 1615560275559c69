// Writes that cannot destroy, as a user meets them: a full disk is a clear error (exit 1) naming
// the file and the OS's reason, never a crash; a link planted at a guessable temporary name is
// never written through; an output that cannot be written is a usage error (exit 2) before any
// work; SIGTERM and SIGINT in the middle of a run end it with 143 and 130. In every case the old
// output is as it was and no temporary file is left.

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../common/small_disk.hpp"
#include "../common/temp_dir.hpp"
#include "run.hpp"

extern char** environ;

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using tactile::test::Started;
using ::testing::HasSubstr;

namespace {

const fs::path kDemo = tactile::test::demo_dir();

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Files under `dir` whose name is a temporary file's (".NAME.<hex>.tmp") or the old ".partial".
std::vector<fs::path> temporary_files(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.ends_with(".tmp") || name.ends_with(".partial")) found.push_back(it->path());
  }
  return found;
}

class SafeWrite : public ::testing::Test {
 protected:
  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

TEST_F(SafeWrite, MapOnAFullDiskSaysSoAndKeepsTheOldMovie) {
  const tactile::test::SmallDisk disk(64);
  const fs::path out = disk / "movie.h5";
  std::ofstream(out) << "old movie";
  disk.fill();
  const auto r = run_tactile("map " + (kDemo / "strain.h5").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("cannot write " + out.string() + ": No space left on device"));
  EXPECT_EQ(bytes(out), "old movie");
  EXPECT_THAT(temporary_files(disk.path()), ::testing::IsEmpty());
}

TEST_F(SafeWrite, CaptureOnAFullDiskSaysSoAndKeepsTheOldStrain) {
  const tactile::test::SmallDisk disk(64);
  const fs::path out = disk / "strain.h5";
  std::ofstream(out) << "old strain";
  disk.fill();
  const auto r = run_tactile("capture " + (kDemo / "frames").string() +
                             " --px-per-mm 62 --min-track 2 --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("cannot write " + out.string() + ": No space left on device"));
  EXPECT_EQ(bytes(out), "old strain");
  EXPECT_THAT(temporary_files(disk.path()), ::testing::IsEmpty());
}

TEST_F(SafeWrite, ALinkAtTheOldPartialNameIsNotWrittenThrough) {
  const fs::path victim = dir_ / "victim.h5";
  fs::copy_file(kDemo / "strain.h5", victim);
  const std::string before = bytes(victim);
  fs::create_symlink(victim, dir_ / "movie.h5.partial");
  std::ofstream(dir_ / "movie.csv.partial") << "stale half of an interrupted run";
  const auto r = run_tactile("map " + victim.string() + " --out " + (dir_ / "movie.h5").string() +
                             " --csv " + (dir_ / "movie.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(bytes(victim), before);
  EXPECT_TRUE(fs::is_symlink(dir_ / "movie.h5.partial"));
  EXPECT_EQ(bytes(dir_ / "movie.csv.partial"), "stale half of an interrupted run");
  EXPECT_EQ(bytes(dir_ / "movie.csv").rfind("frame,", 0), 0U) << bytes(dir_ / "movie.csv");
}

TEST_F(SafeWrite, AnOutputThatCannotBeWrittenIsAUsageErrorBeforeTheWork) {
  const std::string map = "map " + (kDemo / "strain.h5").string() + " --out ";
  auto r = run_tactile(map + (dir_ / "missing" / "m.h5").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("--out " + (dir_ / "missing" / "m.h5").string() + ": the folder " +
                        (dir_ / "missing").string() + " does not exist"));
  r = run_tactile(map + dir_.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--out " + dir_.string() + ": is a folder"));
  std::ofstream(dir_ / "file") << "a file";
  std::ofstream(dir_ / "tiny.json") << R"({"name": "tiny", "seed": 1, "sources": [{"name": "gt",
    "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
    "layouts": ["stress"], "methods": ["integrated"], "parameters": {"rate_hz": 100}})";
  r = run_tactile("experiment " + (dir_ / "tiny.json").string() + " --out " +
                  (dir_ / "file").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--out " + (dir_ / "file").string() + ": is a file"));
  EXPECT_EQ(bytes(dir_ / "file"), "a file");
}

// A folder that cannot be written, made in two ways that hold although the tests run as root
// (root ignores mode bits, so chmod 0555 would prove nothing): a tmpfs the test mounts
// read-only (access() answers EROFS to root too), and, independent of file system and
// privileges, a path whose parent is a regular file. For map and capture, every output there is
// a usage error (exit 2) naming the option and the reason, found before the work: no line of
// the work is printed and nothing is written.
TEST_F(SafeWrite, AnOutputInAFolderThatCannotBeWrittenIsRefusedBeforeTheWork) {
  const tactile::test::SmallDisk read_only(64, true);
  std::ofstream(dir_ / "file") << "a file";
  const fs::path strain = kDemo / "strain.h5";
  const std::string capture = "capture " + (kDemo / "frames").string() + " --px-per-mm 62 ";
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"map " + strain.string() + " --out " + (read_only / "m.h5").string(),
       "--out " + (read_only / "m.h5").string() + ": cannot write in the folder " +
           read_only.path().string() + ": Read-only file system"},
      {"map " + strain.string() + " --out " + (dir_ / "m.h5").string() + " --csv " +
           (read_only / "m.csv").string(),
       "--csv " + (read_only / "m.csv").string() + ": cannot write in the folder"},
      {"map " + strain.string() + " --out " + (dir_ / "file" / "m.h5").string(),
       "--out " + (dir_ / "file" / "m.h5").string() + ": " + (dir_ / "file").string() +
           " is not a folder"},
      {capture + "--out " + (read_only / "s.h5").string(),
       "--out " + (read_only / "s.h5").string() + ": cannot write in the folder " +
           read_only.path().string() + ": Read-only file system"},
      {capture + "--out " + (dir_ / "s.h5").string() + " --maps " + (read_only / "maps").string(),
       "--maps " + (read_only / "maps").string() + ": cannot write in the folder " +
           read_only.path().string() + ": Read-only file system"},
      {capture + "--out " + (dir_ / "s.h5").string() + " --csv " + (dir_ / "file" / "csv").string(),
       "--csv " + (dir_ / "file" / "csv").string() + ": " + (dir_ / "file").string() +
           " is not a folder"},
  };
  for (const auto& c : cases) {
    const auto r = run_tactile(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
    // The error is all it printed: the work's first lines (capture's choice of detector, map's
    // summary) never came.
    EXPECT_EQ(r.output.rfind("tactile " + c.args.substr(0, c.args.find(' ')) + ": error: ", 0), 0U)
        << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "s.h5"));
  EXPECT_TRUE(fs::is_empty(read_only.path()));
  EXPECT_EQ(bytes(dir_ / "file"), "a file");
}

// An experiment of many movies, long enough to be stopped in the middle: about 4 s on two idle
// cores, so that every moment below falls inside it (with 1500 frames it took 0.6 s, and the
// 500 ms moment sometimes came after its end).
const char* kLong = R"({"name": "long", "seed": 1,
  "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 6000},
               "grid_spacing_mm": 0.6}],
  "layouts": ["stress", "latero"], "methods": ["integrated", "profile", "proportional"],
  "parameters": {"rate_hz": 100}})";

// Stops the experiment with `sig` `after` into its run, or (after < 0) as soon as one of its
// temporary files is seen: it must end by that signal, leave no temporary file, and leave the
// old metrics.csv (written last) as it was.
void stop_experiment(const fs::path& dir, std::chrono::milliseconds after, int sig) {
  const fs::path exp = dir / "long.json";
  std::ofstream(exp) << kLong;
  static int runs = 0;
  const fs::path out = dir / ("out" + std::to_string(runs++));
  fs::create_directories(out);
  std::ofstream(out / "metrics.csv") << "old metrics";
  Started experiment({"experiment", exp.string(), "--out", out.string(), "--threads", "2"},
                     dir / "log.txt");
  if (after.count() >= 0) {
    std::this_thread::sleep_for(after);
  } else {
    // A temporary file may be renamed into place between two looks: what counts is that one
    // was seen, not that it is still there.
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    bool seen = false;
    while (!(seen = !temporary_files(out).empty()) && std::chrono::steady_clock::now() < give_up) {
    }
    EXPECT_TRUE(seen) << "no temporary file seen";
  }
  experiment.signal(sig);
  const Started::Ended end = experiment.wait(60);
  ASSERT_TRUE(end.ended) << "still running 60 s after the signal";
  // Ended by the signal, or, when it came while `tactile` was still starting, by its answer
  // to it ("stopped by ... before it began", the signal's exit code).
  const std::string log = bytes(dir / "log.txt");
  const bool answered = end.killed_by == 0 && log.find("stopped by") != std::string::npos;
  ASSERT_TRUE(end.killed_by != 0 || answered)
      << "the experiment ended before the signal, or by itself, at " << after.count()
      << " ms: " << log;
  EXPECT_EQ(answered ? end.exit_code : 128 + end.killed_by, sig == SIGTERM ? 143 : 130);
  EXPECT_THAT(temporary_files(out), ::testing::IsEmpty()) << after.count() << " ms";
  EXPECT_EQ(bytes(out / "metrics.csv"), "old metrics") << after.count() << " ms";
}

TEST_F(SafeWrite, SigtermOrSigintDuringAnExperimentLeavesNoTemporaryFile) {
  const std::pair<int, int> moments[] = {
      {-1, SIGTERM}, {-1, SIGINT}, {100, SIGTERM}, {250, SIGINT}, {500, SIGTERM}};
  for (const auto& [ms, sig] : moments) stop_experiment(dir_, std::chrono::milliseconds(ms), sig);
}

// Found by the third hostile-input run: SIGTERM to `map --out M.h5 --csv C.csv` while it wrote
// the CSV left the new movie beside the old CSV (or none). Both outputs are now committed
// together at the end: stopped before, neither is replaced and no temporary file is left.
TEST_F(SafeWrite, SigtermWhileMapWritesItsCsvReplacesNeitherOutput) {
  // 32 x 32 contactors at 1000 Hz for the demo's 3 s: a CSV of about 25 MB, long enough to
  // be caught while it is written.
  const fs::path layout = dir_ / "big.json";
  std::ofstream(layout) << R"({"name": "big", "rows": 32, "cols": 32, "pitch_mm": [0.2, 0.2],
    "contactor_size_mm": [0.1, 0.1], "deflection_axis": "x", "deflection_range_um": [-50, 50],
    "max_rate_hz": 1000})";
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  std::ofstream(out / "M.h5") << "old movie";
  std::ofstream(out / "C.csv") << "old csv";
  Started map({"map", (kDemo / "strain.h5").string(), "--layout", layout.string(), "--rate-hz",
               "1000", "--out", (out / "M.h5").string(), "--csv", (out / "C.csv").string()},
              dir_ / "log.txt");
  const auto csv_begun = [&] {
    return std::ranges::any_of(temporary_files(out), [](const fs::path& p) {
      return p.filename().string().starts_with(".C.csv.");
    });
  };
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!csv_begun() && std::chrono::steady_clock::now() < give_up) {
  }
  ASSERT_TRUE(csv_begun()) << "the CSV was never seen being written: " << bytes(dir_ / "log.txt");
  map.signal(SIGTERM);
  const Started::Ended end = map.wait(60);
  ASSERT_TRUE(end.ended) << "still running 60 s after the signal";
  ASSERT_EQ(end.killed_by, SIGTERM) << "ended otherwise: " << bytes(dir_ / "log.txt");
  // Compared without printing: a replaced movie is megabytes of binary.
  EXPECT_TRUE(bytes(out / "M.h5") == "old movie") << "M.h5 was replaced";
  EXPECT_TRUE(bytes(out / "C.csv") == "old csv") << "C.csv was replaced";
  EXPECT_THAT(temporary_files(out), ::testing::IsEmpty());
}

// Found by the hostile-input run: SIGINT to `capture --out --csv --maps` while it wrote its
// maps left the new strain movie and CSV files beside old maps. The maps are now committed with
// them, and a stop while they are written replaces none of the outputs and says so.
TEST_F(SafeWrite, SigintWhileCaptureWritesItsMapsReplacesNoOutput) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "csv");
  fs::create_directories(out / "maps");
  std::ofstream(out / "s.h5") << "old strain";
  std::ofstream(out / "csv" / "edges.csv") << "old edges";
  std::ofstream(out / "maps" / "strain_000.png") << "old map";
  Started capture({"capture", (kDemo / "frames").string(), "--calib",
                   (kDemo / "calibration.json").string(), "--out", (out / "s.h5").string(), "--csv",
                   (out / "csv").string(), "--maps", (out / "maps").string()},
                  dir_ / "log.txt");
  // The demo's 179 maps take a few seconds to draw; progress shows the first quarter of them.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (bytes(dir_ / "log.txt").find("  maps ") == std::string::npos &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_THAT(bytes(dir_ / "log.txt"), HasSubstr("  maps "));
  capture.signal(SIGINT);
  const Started::Ended end = capture.wait(60);
  ASSERT_TRUE(end.ended) << "still running 60 s after the signal";
  const std::string log = bytes(dir_ / "log.txt");
  ASSERT_EQ(end.killed_by, 0) << log;
  EXPECT_EQ(end.exit_code, 130) << log;
  EXPECT_THAT(log, HasSubstr("capture: stopped by SIGINT while writing its outputs: none of them "
                             "was replaced"));
  EXPECT_TRUE(bytes(out / "s.h5") == "old strain") << "s.h5 was replaced";
  EXPECT_EQ(bytes(out / "csv" / "edges.csv"), "old edges");
  EXPECT_FALSE(fs::exists(out / "csv" / "tracks.csv"));
  EXPECT_EQ(bytes(out / "maps" / "strain_000.png"), "old map");
  EXPECT_FALSE(fs::exists(out / "maps" / "strain_001.png"));
  EXPECT_THAT(temporary_files(out), ::testing::IsEmpty());
}

// A stop while it measures (the frames read on OpenCV's worker threads) is taken at the next
// progress step: a message and 130, not the end of the process by a worker's default action.
TEST_F(SafeWrite, SigtermWhileCaptureMeasuresWritesNothingAndSaysSo) {
  const fs::path out = dir_ / "s.h5";
  std::ofstream(out) << "old strain";
  Started capture({"capture", (kDemo / "frames").string(), "--calib",
                   (kDemo / "calibration.json").string(), "--out", out.string()},
                  dir_ / "log.txt");
  ASSERT_TRUE(capture.wait_until_watching(SIGTERM, 60)) << bytes(dir_ / "log.txt");
  capture.signal(SIGTERM);
  const Started::Ended end = capture.wait(60);
  ASSERT_TRUE(end.ended) << "still running 60 s after the signal";
  const std::string log = bytes(dir_ / "log.txt");
  ASSERT_EQ(end.killed_by, 0) << log;
  EXPECT_EQ(end.exit_code, 143) << log;
  EXPECT_THAT(log, ::testing::ContainsRegex("capture: stopped by SIGTERM at [a-z]+ [0-9]+/[0-9]+: "
                                            "nothing written"));
  EXPECT_EQ(bytes(out), "old strain");
  EXPECT_THAT(temporary_files(dir_), ::testing::IsEmpty());
}

}  // namespace
