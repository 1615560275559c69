// `tactile view` as a user runs it, in a real window under Xvfb: the demo's movie with its
// source strain movie found through the movie's provenance, and malformed command lines.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/display/viewer.hpp"

namespace tactile::display {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string command = std::string(TACTILE_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr)
    r.output += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// One short demo (movie.h5 mapped from strain.h5) for every test of this file: 40 frames, as
// tracks shorter than 30 frames are rejected and fewer frames leave no strain at all.
class ViewCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new tactile::test::TempDir("suite");
    dir_ = tmp_->path();
    demo_ = run("demo --headless --frames 40 --out " + dir_.string());
  }
  static void TearDownTestSuite() { delete tmp_; }
  static tactile::test::TempDir* tmp_;
  static fs::path dir_;
  static CliRun demo_;
};
tactile::test::TempDir* ViewCli::tmp_ = nullptr;
fs::path ViewCli::dir_;
CliRun ViewCli::demo_;

TEST_F(ViewCli, ScreenshotShowsTheSourceStrainFoundThroughTheProvenance) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  ASSERT_EQ(demo_.exit_code, 0) << demo_.output;
  const fs::path png = dir_ / "view.png";
  const CliRun r =
      run("view " + (dir_ / "movie.h5").string() + " --at 0.1 --screenshot " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("with the source strain field"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 1000u);
  // --no-strain leaves it out; an explicit --strain names the same file.
  const CliRun without =
      run("view " + (dir_ / "movie.h5").string() + " --no-strain --screenshot " + png.string());
  ASSERT_EQ(without.exit_code, 0) << without.output;
  EXPECT_EQ(without.output.find("strain"), std::string::npos) << without.output;
  const CliRun with = run("view " + (dir_ / "movie.h5").string() + " --strain " +
                          (dir_ / "strain.h5").string() + " --screenshot " + png.string());
  EXPECT_EQ(with.exit_code, 0) << with.output;
  EXPECT_NE(with.output.find("with the source strain field"), std::string::npos) << with.output;
}

TEST_F(ViewCli, MalformedCommandLinesAreClearErrors) {
  ASSERT_EQ(demo_.exit_code, 0) << demo_.output;
  const std::string movie = (dir_ / "movie.h5").string();
  // A tactile movie given as the strain movie: a failure naming the expected format.
  CliRun r =
      run("view " + movie + " --strain " + movie + " --screenshot " + (dir_ / "x.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("tactile-strain-movie"), std::string::npos) << r.output;
  // Usage errors: exit 2, nothing drawn.
  r = run("view " + movie + " --strain " + (dir_ / "strain.h5").string() + " --no-strain");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("excludes"), std::string::npos) << r.output;
  r = run("view " + movie + " --at -1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run("view " + movie + " --strain " + (dir_ / "missing.h5").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // A screenshot into a folder that does not exist: found before any drawing, a usage error
  // naming the file and the missing folder.
  r = run("view " + movie + " --screenshot " + (dir_ / "no-such-dir" / "x.png").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("x.png"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
}

TEST_F(ViewCli, ASourceStrainMovieWithoutStrainIsLeftOutOrRefusedWhenAskedFor) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  // 20 frames: every track is shorter than the 30 frames capture keeps, so no edges.
  const fs::path short_dir = dir_ / "short";
  const CliRun demo = run("demo --headless --frames 20 --out " + short_dir.string());
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  const std::string movie = (short_dir / "movie.h5").string();
  CliRun r = run("view " + movie + " --screenshot " + (short_dir / "v.png").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not showing the source strain movie"), std::string::npos) << r.output;
  r = run("view " + movie + " --strain " + (short_dir / "strain.h5").string() + " --screenshot " +
          (short_dir / "v.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("strain.h5: strain movie has no edge"), std::string::npos) << r.output;
}

// Without a display attached, `play` opens the emulator window; SIGTERM closes it and the
// command exits 143 after saying so. (SIGTERM: the shell that backgrounds the command leaves it
// SIGINT ignored.)
TEST_F(ViewCli, PlayWindowStopsOnSigterm) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  ASSERT_EQ(demo_.exit_code, 0) << demo_.output;
  const fs::path log = dir_ / "play-window.log";
  const CliRun r =
      run("play " + (dir_ / "movie.h5").string() + " --loops 1000 > " + log.string() +
          " 2>&1 & P=$!; sleep 2; kill -TERM $P; wait $P; echo rc=$?; cat " + log.string());
  EXPECT_NE(r.output.find("opening the emulator window"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("window closed by a stop request"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("play: stopped by SIGTERM"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rc=143"), std::string::npos) << r.output;
}

// `tactile live --window` as a user runs it on a rehearsal (a real print moved by a wave): the
// session plays to its end in the window, whose last image is written; bad combinations are
// usage errors.
TEST(LiveWindowCli, TheSessionIsShownAndItsLastImageWritten) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  tactile::test::TempDir dir;
  const fs::path wave = dir.path() / "wave";
  const CliRun synth = run("synth " + wave.string() + " --from-print " + TACTILE_TEST_DATA_DIR +
                           "/polyu-hrf-pores/image_12.jpg --px-per-mm 47 --warp wave --frames 40");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const fs::path png = dir.path() / "live.png";
  const CliRun r =
      run("live " + wave.string() +
          " --px-per-mm 47 --rate-hz 10 --queue-frames 30 --window --screenshot " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("40 in, 40 processed, 0 dropped"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 10000u);

  EXPECT_EQ(run("live " + wave.string() + " --px-per-mm 47 --window --headless").exit_code, 2);
  EXPECT_EQ(
      run("live " + wave.string() + " --px-per-mm 47 --headless --screenshot x.png").exit_code, 2);
  const CliRun no_folder = run("live " + wave.string() + " --px-per-mm 47 --window --screenshot " +
                               (dir.path() / "none" / "x.png").string());
  EXPECT_EQ(no_folder.exit_code, 2) << no_folder.output;
  EXPECT_NE(no_folder.output.find("x.png"), std::string::npos) << no_folder.output;
}

}  // namespace
}  // namespace tactile::display
