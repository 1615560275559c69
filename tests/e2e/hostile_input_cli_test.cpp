// Hostile numbers on every numeric option that takes a real number, and runs that would produce
// nothing useful: a usage error (exit 2) naming the option, or a failed run (exit 1) saying why,
// never a success, a crash or a library's raw message.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "../common/file_text.hpp"
#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/common/version.hpp"

using tactile::test::demo_dir;
using tactile::test::run_tactile;
using tactile::test::test_data;
using ::testing::AnyOf;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

struct NumericOption {
  std::string command;  // with every other required argument; the option is appended
  std::string option;
  bool positive_minimum;  // a tiny positive number is out of range too
};

TEST(HostileInput, NonFiniteAndAbsurdNumbersAreUsageErrorsNamingTheOption) {
  const std::string strain = (demo_dir() / "strain.h5").string();
  const std::string frames = demo_dir().string();
  const std::string prints = test_data("polyu-hrf-pores").string();
  const std::string recordings = test_data("biotac-materials").string();
  const std::string labels = (test_data("biotac-materials") / "labels.csv").string();
  const std::vector<NumericOption> options = {
      {"capture " + frames + " --out x.h5", "--px-per-mm", true},
      {"capture " + frames + " --px-per-mm 62 --out x.h5", "--rate-hz", true},
      {"capture " + frames + " --px-per-mm 62 --out x.h5", "--refine-window", true},
      {"map " + strain + " --out x.h5", "--rate-hz", true},
      {"map " + strain + " --out x.h5", "--gain", false},
      {"train-pores --prints " + prints + " --px-per-mm 47 --out x.json", "--label-radius-mm",
       true},
      {"train-pores --prints " + prints + " --out x.json", "--px-per-mm", true},
      {"train-pores --prints " + prints + " --px-per-mm 47 --out x.json", "--l2", false},
      {"classify train --recordings " + recordings + " --labels " + labels + " --out x.json", "--c",
       true},
      {"classify train --recordings " + recordings + " --labels " + labels + " --out x.json",
       "--trim", false},
      {"synth x", "--speed", false},
      {"bench latero", "--rate-hz", true},
      {"bench latero", "--seconds", true},
      {"perceive --out x", "--position-variation", false},
      {"emulate --latero", "--seconds", false},
  };
  for (const auto& o : options) {
    std::vector<std::string> values = {"nan", "inf", "-inf", "1e308", "-1e308", "1e999"};
    if (o.positive_minimum) values.push_back("1e-300");
    for (const auto& v : values) {
      const std::string args = o.command + " " + o.option + " " + v;
      const auto r = run_tactile(args);
      EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
      EXPECT_THAT(r.output, HasSubstr(o.option)) << args;
      EXPECT_THAT(r.output, AnyOf(HasSubstr("not a finite number"), HasSubstr("out of range"),
                                  HasSubstr("not a number"), HasSubstr("[0, 0.5)")))
          << args << ": " << r.output;
    }
  }
}

TEST(HostileInput, CaptureThatKeepsNoTrackFailsAndWritesNothing) {
  const tactile::test::TempDir dir("short");
  const auto out = dir.path() / "strain.h5";
  const auto r = run_tactile("capture " + demo_dir().string() +
                             " --px-per-mm 62 --min-track 100000 --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("no strain measured"));
  EXPECT_THAT(r.output, HasSubstr("--min-track 100000"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(HostileInput, ClassifierOfOneClassFailsAndWritesNothing) {
  const tactile::test::TempDir dir("one-class");
  const auto labels = dir.path() / "labels.csv";
  std::ofstream(labels) << "file,class\nmat1_1_bio.csv,mat1\nmat1_2_bio.csv,mat1\n";
  const auto out = dir.path() / "model.json";
  const auto r =
      run_tactile("classify train --recordings " + test_data("biotac-materials").string() +
                  " --labels " + labels.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("at least 2 classes"));
  EXPECT_THAT(r.output, HasSubstr("labels.csv"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A run that needs more memory than the process may have (an address-space limit the test sets
// with the shell's ulimit: an experiment whose one movie, 256 x 256 contactors at 700 Hz for
// 17 s, needs about 3 GB) ends as a failed run, exit 1, with one line naming the command, not
// an abort with std::bad_alloc.
TEST(HostileInput, OutOfMemoryIsAFailedRunNamingTheCommand) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: ulimit -v cannot bound "
                  "a sanitized program";
#endif
  const tactile::test::TempDir tmp("out-of-memory");
  const auto dir = tmp.path();
  std::ofstream(dir / "big.json") << R"({"name": "big", "rows": 256, "cols": 256,
    "pitch_mm": [0.05, 0.05], "contactor_size_mm": [0.02, 0.02], "deflection_axis": "x",
    "deflection_range_um": [-50, 50], "max_rate_hz": 700})";
  std::ofstream(dir / "exp.json") << R"({"name": "mem", "seed": 1,
    "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 1000},
                 "grid_spacing_mm": 0.6}],
    "layouts": ["big.json"], "methods": ["proportional"], "write_movies": false})";
  const std::string cmd = "ulimit -v 1500000 && " + std::string(TACTILE_CLI_PATH) + " experiment " +
                          (dir / "exp.json").string() + " --out " + (dir / "out").string() +
                          " --threads 1 2>&1; echo \"exit=$?\"";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, pipe)) > 0;) output.append(buf, n);
  pclose(pipe);
  EXPECT_THAT(output, HasSubstr("tactile experiment: error: out of memory")) << output;
  EXPECT_THAT(output, HasSubstr("exit=1")) << output;
  EXPECT_THAT(output, ::testing::Not(HasSubstr("std::bad_alloc"))) << output;
}

}  // namespace

// Frames too small to hold a triangle of tracked points: strain frames come out, but with no
// edge in any of them; that is no strain measured, not a movie of a still display.
TEST(HostileInput, CaptureOfFramesWithNoEdgeFailsAndWritesNothing) {
  const tactile::test::TempDir dir("tiny");
  const tactile::capture::GrayImage pixel{1, 1, {128}};
  tactile::capture::write_frames(dir.path() / "frames", {pixel, pixel});
  const auto out = dir.path() / "strain.h5";
  const auto r = run_tactile("capture " + (dir.path() / "frames").string() +
                             " --px-per-mm 62 --min-track 2 --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("no strain measured")) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A damaged frame among good ones: libpng would print "libpng error: ..." on stderr before the
// program's own message; the only line about the file must be the program's one error line.
TEST(HostileInput, DamagedPngFrameGivesOnlyTheProgramsOneLineNamingIt) {
  const tactile::test::TempDir dir("damaged-png");
  tactile::capture::GrayImage frame{64, 48, std::vector<std::uint8_t>(64 * 48)};
  for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
    frame.pixels[i] = static_cast<std::uint8_t>(i * 7 % 251);
  }
  struct Damage {
    std::string name;
    std::string reason;
    std::function<void(std::string&)> apply;
  };
  const std::vector<Damage> damages = {{"truncated", "the file ends early (truncated)",
                                        [](std::string& png) { png.resize(png.size() / 2); }},
                                       {"bad-crc", "IHDR: CRC error", [](std::string& png) {
                                          png[29] = static_cast<char>(png[29] ^ 0xFF);
                                        }}};
  for (const Damage& damage : damages) {
    const auto frames = dir.path() / damage.name;
    tactile::capture::write_frames(frames, {frame, frame, frame});
    const auto bad = frames / tactile::capture::frame_file_name(1);
    std::string bytes;
    {
      std::ifstream in(bad, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    damage.apply(bytes);
    std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes;
    const auto out = dir.path() / (damage.name + ".h5");
    const auto r = run_tactile("capture " + frames.string() +
                               " --px-per-mm 62 --min-track 2 --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    // Before the frame, capture's own notes (its choices, its progress); then its error, last.
    std::vector<std::string> lines;
    std::istringstream text(r.output);
    for (std::string line; std::getline(text, line);) lines.push_back(line);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.back(), "tactile capture: error: " + bad.string() + ": not a readable image (" +
                                damage.reason + ")");
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
      EXPECT_TRUE(lines[i].rfind("capture: ", 0) == 0 || lines[i].rfind("  ", 0) == 0)
          << "not one of capture's own notes: " << lines[i];
      EXPECT_THAT(lines[i], ::testing::Not(HasSubstr(bad.filename().string())));
    }
    EXPECT_THAT(r.output, ::testing::Not(HasSubstr("libpng")));
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// Found by the third hostile-input run: calibrating an image with no dot grid, or too small to
// hold one, said so without naming the image.
TEST(HostileInput, CalibrateOfAnImageWithNoGridNamesItAndWritesNothing) {
  const tactile::test::TempDir dir("no-grid");
  const std::vector<std::uint8_t> white(200 * 150, 255);
  const std::vector<std::pair<std::string, tactile::capture::GrayImage>> images = {
      {"blank.png", {200, 150, white}}, {"one-pixel.png", {1, 1, {0}}}};
  for (const auto& [name, image] : images) {
    const auto png = dir.path() / name;
    tactile::capture::write_png(png, image);
    const auto out = dir.path() / (name + ".json");
    const auto r = run_tactile("calibrate " + png.string() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_THAT(r.output,
                HasSubstr("tactile calibrate: error: " + png.string() + ": no dot grid found"))
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << name;
  }
}

// A calibration made for another image size (its image_width_px edited to 64) maps every pixel
// wrong: `features` used it without a word and `capture` failed only after choosing its
// detector, without naming the file. Both now name the calibration file and the image.
TEST(HostileInput, CalibrationForAnotherImageSizeNamesTheFileBeforeAnyWork) {
  const tactile::test::TempDir dir("calib-size");
  std::string text = tactile::test::file_text(demo_dir() / "calibration.json");
  const std::string width = "\"image_width_px\": 640";
  const auto at = text.find(width);
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, width.size(), "\"image_width_px\": 64");
  const auto calib = dir.path() / "narrow.json";
  std::ofstream(calib) << text;
  const std::string frame = (demo_dir() / "frames" / "frame_000.png").string();
  const auto features = run_tactile("features " + frame + " --calib " + calib.string());
  EXPECT_EQ(features.exit_code, 1) << features.output;
  EXPECT_THAT(features.output,
              HasSubstr(calib.string() + ": the calibration is for 64 x 484 px images, but " +
                        frame + " is 640 x 484 px"));
  const auto out = dir.path() / "strain.h5";
  const auto capture = run_tactile("capture " + (demo_dir() / "frames").string() + " --calib " +
                                   calib.string() + " --out " + out.string());
  EXPECT_EQ(capture.exit_code, 1) << capture.output;
  EXPECT_THAT(capture.output, HasSubstr(calib.string() + ": the calibration is for 64 x 484 px"));
  EXPECT_THAT(capture.output, Not(HasSubstr("pores:"))) << "no detection before the check";
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Found by the third hostile-input run: `play --preview /proc/version` played the whole movie and
// then printed OpenCV's "could not find encoder for the specified extension". Every preview path
// that cannot be written is a usage error naming --preview and why, before the movie is read.
TEST(HostileInput, PlayPreviewThatCannotBeWrittenIsAUsageErrorBeforeAnyWork) {
  const tactile::test::TempDir dir("preview");
  const std::string movie = (demo_dir() / "movie.h5").string();
  const auto d = dir.path().string();
  const std::vector<std::pair<std::string, std::string>> previews = {
      {"/proc/version", "the name must end in .png"},
      {d + "/preview", "the name must end in .png"},
      {d + "/preview.jpg", "the name must end in .png"},
      {d, "is a folder; give a file name"},
      {d + "/missing/preview.png", "the folder " + d + "/missing does not exist"},
      // The superuser passes every permission check there; only trying tells.
      {"/proc/preview.png", "/proc"},
      {movie, "would write over the input MOVIE_H5"}};
  for (const auto& [preview, why] : previews) {
    const auto r = run_tactile("play --headless " + movie + " --preview " + preview);
    EXPECT_EQ(r.exit_code, 2) << preview << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("tactile play: error: --preview " + preview)) << r.output;
    EXPECT_THAT(r.output, HasSubstr(why)) << r.output;
    EXPECT_THAT(r.output, ::testing::Not(HasSubstr("OpenCV"))) << r.output;
    EXPECT_THAT(r.output, ::testing::Not(HasSubstr("frames played"))) << preview;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  // The extension in capitals is still a PNG.
  const auto r = run_tactile("play --headless " + movie + " --preview " + d + "/preview.PNG");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "preview.PNG"));
}

// Found by the third hostile-input run: `synth --seed -1` rendered with seed 18446744073709551615
// (CLI11 wraps a negative number into an unsigned option) and wrote that into scene.json.
TEST(HostileInput, ANegativeSeedIsAUsageError) {
  const tactile::test::TempDir dir("seed");
  const auto out = (dir.path() / "out").string();
  for (const std::string& command :
       {"synth " + out + " --frames 2", "demo --headless --frames 2 --out " + out,
        "perceive --out " + out}) {
    for (const char* seed : {"-1", "-0", "1.5", "1e3", "18446744073709551616"}) {
      const auto r = run_tactile(command + " --seed " + seed);
      EXPECT_EQ(r.exit_code, 2) << command << " --seed " << seed << ": " << r.output;
      EXPECT_THAT(r.output, HasSubstr(std::string("--seed: ") + seed +
                                      " is not a whole number from 0 to 2^64 - 1"))
          << r.output;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto r = run_tactile("synth " + out + " --frames 2 --seed 18446744073709551615");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// Found by the third hostile-input run: a print too small to warp was refused without naming it.
TEST(HostileInput, SynthFromAPrintTooSmallNamesIt) {
  const tactile::test::TempDir dir("tiny-print");
  const auto png = dir.path() / "tiny.png";
  tactile::capture::write_png(png, {1, 1, {0}});
  const auto r = run_tactile("synth " + (dir.path() / "out").string() +
                             " --frames 3 --from-print " + png.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--from-print " + png.string() +
                                  ": invalid print warp: the print "
                                  "is 1 x 1 px"))
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "frame_000.png"));
}

// A program's library search path must not take in the folder it is run from: a file of the
// name of a library it needs, planted there, would be loaded in place of the system's (an empty
// entry in a RUNPATH is the current folder). Every library `tactile` loads is planted here as a
// file that is no library at all, so loading any one of them fails the start.
TEST(HostileInput, LibrariesPlantedInTheWorkingFolderAreNotLoaded) {
  const tactile::test::TempDir dir("planted-libraries");
  FILE* ldd = popen((std::string("ldd ") + TACTILE_CLI_PATH).c_str(), "r");
  ASSERT_NE(ldd, nullptr);
  std::string listing;
  std::array<char, 4096> buf{};
  for (std::size_t n = 0; (n = fread(buf.data(), 1, buf.size(), ldd)) > 0;) {
    listing.append(buf.data(), n);
  }
  ASSERT_EQ(pclose(ldd), 0) << listing;
  int planted = 0;
  std::istringstream lines(listing);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string name, arrow;
    if (words >> name >> arrow && arrow == "=>" && name.find('/') == std::string::npos) {
      std::ofstream(dir.path() / name) << "not a shared library\n";
      ++planted;
    }
  }
  ASSERT_GT(planted, 20) << listing;
  const std::filesystem::path was = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  const auto r = run_tactile("--version");
  std::filesystem::current_path(was);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr(std::string("tactile ") + tactile::kVersion)) << r.output;
}
