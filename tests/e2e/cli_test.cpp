// The command line as a user meets it: help, wrong usage (exit 2), bad files (exit 1), with a
// message that names the problem, and never a crash.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/movie/movie_io.hpp"

namespace fs = std::filesystem;
using tactile::test::demo_dir;
using tactile::test::run_tactile;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {}  // namespace

TEST(Cli, HelpListsEverySubcommand) {
  const auto r = run_tactile("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* cmd : {"demo", "synth", "calibrate", "features", "capture", "map", "play",
                          "view", "devices", "info", "export", "import"}) {
    EXPECT_THAT(r.output, HasSubstr(cmd)) << cmd;
  }
}

TEST(Cli, SubcommandHelpExplainsOptions) {
  const auto r = run_tactile("capture --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--px-per-mm"));
  EXPECT_THAT(r.output, HasSubstr("--span"));
}

TEST(Cli, NoSubcommandIsUsageError) {
  const auto r = run_tactile("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("subcommand"));
}

TEST(Cli, UnknownSubcommandIsUsageError) {
  const auto r = run_tactile("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("frobnicate"));
}

TEST(Cli, MissingRequiredArgumentIsNamed) {
  const auto r = run_tactile("map");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("STRAIN_H5"));
}

TEST(Cli, BadOptionValueIsNamed) {
  const tactile::test::TempDir d_tmp("badvalue");
  const std::filesystem::path& d = d_tmp.path();
  const auto r = run_tactile("demo --out " + d.string() + " --frames many");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--frames"));
  const auto r2 = run_tactile("synth " + d.string() + " --scene volcano");
  EXPECT_EQ(r2.exit_code, 2);
  // The scene's names come from its table, in the words of every table's choice.
  EXPECT_THAT(r2.output, HasSubstr("--scene: unknown value 'volcano' (known: bump, hole, "
                                   "flat-slide, flat-rotate, flat-stick-slip)"));
}

TEST(Cli, CaptureNeedsACalibration) {
  const tactile::test::TempDir d_tmp("nocalib");
  const std::filesystem::path& d = d_tmp.path();
  const auto r = run_tactile("capture " + d.string() + " --out " + (d / "s.h5").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--px-per-mm"));
}

TEST(Cli, CalibAndScaleTogetherIsUsageError) {
  const tactile::test::TempDir d_tmp("both");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "c.json") << "{}";
  const auto r = run_tactile("features " + (d / "c.json").string() + " --calib " +
                             (d / "c.json").string() + " --px-per-mm 40");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("excludes"));
}

TEST(Cli, MissingFileIsNamed) {
  const auto r = run_tactile("info /nonexistent/movie.h5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("/nonexistent/movie.h5"));
}

TEST(Cli, NonHdf5MovieIsAClearError) {
  const tactile::test::TempDir d_tmp("nonhdf5");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "movie.h5") << "this is not a movie\n";
  for (const std::string cmd : {"play --headless", "info", "view"}) {
    const auto r = run_tactile(cmd + " " + (d / "movie.h5").string());
    EXPECT_EQ(r.exit_code, 1) << cmd << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("not an HDF5 file")) << cmd;
  }
}

TEST(Cli, NonImageIsAClearError) {
  const tactile::test::TempDir d_tmp("nonimage");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "finger.png") << "PNG? no.\n";
  const auto r = run_tactile("features " + (d / "finger.png").string() + " --px-per-mm 47");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("finger.png"));
}

namespace {

// A 24-bit BMP of `w` x `h` mid-grey pixels, written by hand (no image library in these tests).
void write_grey_bmp(const std::filesystem::path& path, int w, int h) {
  const int row = (3 * w + 3) / 4 * 4;
  const int size = 54 + row * h;
  std::string b(static_cast<std::size_t>(size), '\0');
  const auto put = [&b](int at, int value, int bytes) {
    for (int i = 0; i < bytes; ++i)
      b[static_cast<std::size_t>(at + i)] = static_cast<char>(value >> (8 * i));
  };
  b[0] = 'B';
  b[1] = 'M';
  put(2, size, 4);
  put(10, 54, 4);
  put(14, 40, 4);
  put(18, w, 4);
  put(22, h, 4);
  put(26, 1, 2);
  put(28, 24, 2);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < 3 * w; ++x) b[static_cast<std::size_t>(54 + y * row + x)] = '\x80';
  }
  std::ofstream(path, std::ios::binary) << b;
}

}  // namespace

// An image of a pixel or a few holds no ridge: reporting "0 pores" in it would read as a
// measurement, so it is refused naming the file and its size, like any unusable image.
TEST(Cli, ImageTooSmallForAFingerprintIsRefused) {
  const tactile::test::TempDir d_tmp("tiny");
  const std::filesystem::path& d = d_tmp.path();
  write_grey_bmp(d / "one.bmp", 1, 1);
  write_grey_bmp(d / "narrow.bmp", 15, 40);
  write_grey_bmp(d / "enough.bmp", 16, 16);
  const auto one = run_tactile("features " + (d / "one.bmp").string() + " --px-per-mm 47");
  EXPECT_EQ(one.exit_code, 1) << one.output;
  EXPECT_THAT(one.output, HasSubstr((d / "one.bmp").string() +
                                    ": the image is 1x1 px, too small to hold a fingerprint"));
  const auto narrow = run_tactile("features " + (d / "narrow.bmp").string() + " --px-per-mm 47");
  EXPECT_EQ(narrow.exit_code, 1) << narrow.output;
  EXPECT_THAT(narrow.output, HasSubstr("15x40 px"));
  const auto enough = run_tactile("features " + (d / "enough.bmp").string() + " --px-per-mm 47");
  EXPECT_EQ(enough.exit_code, 0) << enough.output;
}

TEST(Cli, BadCalibrationFileIsNamed) {
  const tactile::test::TempDir d_tmp("badcalib");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "calib.json") << R"({"format": "tactile-calibration", "px_to_mm": [1, 2]})";
  std::ofstream(d / "finger.png") << "x";
  const auto r = run_tactile("features " + (d / "finger.png").string() + " --calib " +
                             (d / "calib.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("calib.json"));
}

TEST(Cli, StrainMovieGivenToPlayIsAClearError) {
  // A strain movie is HDF5 too, but the wrong kind: the player must say so, not crash.
  const tactile::test::TempDir d_tmp("wrongkind");
  const std::filesystem::path& d = d_tmp.path();
  const auto synth = run_tactile("demo --headless --frames 40 --out " + d.string() + " --keep");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const auto r = run_tactile("play --headless " + (d / "strain.h5").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("strain.h5"));
  // What to do about it: map it first.
  EXPECT_THAT(r.output, HasSubstr("a strain movie, not a tactile movie"));
  EXPECT_THAT(r.output, HasSubstr("tactile map"));
  const auto v =
      run_tactile("view " + (d / "strain.h5").string() + " --screenshot " + (d / "v.png").string());
  EXPECT_THAT(v.output, HasSubstr("tactile map"));
}

// Wrong usage helps: a misspelt command or flag is answered with the closest real one, an
// unknown flag is named before a required option it may be the misspelling of, and the hint
// names the command whose help to read.
TEST(Cli, MisspeltCommandSuggestsTheClosest) {
  const auto r = run_tactile("captur x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("unknown command 'captur' (did you mean 'capture'?)"));
  const auto far = run_tactile("zzzzzzzz");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_THAT(far.output, Not(HasSubstr("did you mean")));
}

TEST(Cli, UnknownFlagComesBeforeMissingRequiredAndNamesTheCommand) {
  const tactile::test::TempDir d_tmp("misspelt");
  // --outt for --out: the required --out is missing too, but the misspelling is the news.
  const auto r = run_tactile("capture " + d_tmp.path().string() + " --px-per-mm 47 --outt s.h5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("unknown option '--outt' for `tactile capture` (did you mean "
                                  "'--out'?)"));
  EXPECT_THAT(r.output, HasSubstr("Run `tactile capture --help`"));
  const auto nested = run_tactile("bench map --secondz 3");
  EXPECT_EQ(nested.exit_code, 2);
  EXPECT_THAT(nested.output, HasSubstr("for `tactile bench map`"));
  EXPECT_THAT(nested.output, HasSubstr("Run `tactile bench map --help`"));
}

TEST(Cli, NegativeValuesAreNotTakenForFlags) {
  const auto r = run_tactile("map x.h5 --out y.h5 --reference-frame -1");
  EXPECT_EQ(r.exit_code, 2);  // x.h5 does not exist
  EXPECT_THAT(r.output, Not(HasSubstr("unknown option")));
}

// Full slip has no meaning without the skin's speed: refused by the option's name, before any
// frame is written.
TEST(Cli, FullSlipNeedsATravelSpeed) {
  const tactile::test::TempDir d_tmp("fullslip");
  const std::filesystem::path out = d_tmp.path() / "slip";
  const std::string print = std::string(TACTILE_TEST_DATA_DIR) + "/polyu-hrf-pores/image_12.jpg";
  const auto r =
      run_tactile("synth " + out.string() + " --from-print " + print + " --warp full-slip");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--warp full-slip: needs --travel-speed above 0"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

// synth has two kinds of sequence with two default lengths: its help gives both, and names
// no hidden option (an empty "Excludes:").
TEST(Cli, SynthHelpGivesBothDefaultLengths) {
  const auto r = run_tactile("synth --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("default 180 for a scene, 30 with --from-print"));
  for (std::size_t at = r.output.find("Excludes:"); at != std::string::npos;
       at = r.output.find("Excludes:", at + 1)) {
    const std::size_t next = r.output.find_first_not_of(' ', at + 9);
    EXPECT_TRUE(next != std::string::npos && r.output[next] != '\n') << r.output.substr(at, 40);
  }
}

// A strain movie in which one edge stretched ten thousand fold, a change no skin can have, is
// refused naming the field, the strain frame and the range, and no tactile movie is written.
TEST(Cli, MapRefusesAStrainChangeNoSkinCanHave) {
  const tactile::test::TempDir dir("absurd_strain");
  auto m = tactile::capture::read_strain_movie(demo_dir() / "strain.h5");
  ASSERT_GT(m.frames.size(), 3u);
  ASSERT_GT(m.frames[3].edges.size(), 7u);
  m.frames[3].edges[7].rel_change = 1e4;
  const fs::path strain = dir.path() / "absurd.h5";
  tactile::capture::write_strain_movie(strain, m);
  const fs::path out = dir.path() / "movie.h5";
  const auto r = run_tactile("map " + strain.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("absurd.h5:/frames/edge_rel_change: strain frame 3"));
  EXPECT_THAT(r.output, HasSubstr("changed its length by 10000, out of range: must be from -1 "
                                  "to 10"));
  EXPECT_FALSE(fs::exists(out));
}

// A reference frame the strain movie does not have: a usage error naming the option, the file
// and the frames it has, before anything is written.
TEST(Cli, MapRefusesAReferenceFrameTheStrainMovieDoesNotHave) {
  const tactile::test::TempDir dir("reference_frame");
  const fs::path strain = demo_dir() / "strain.h5";
  const auto m = tactile::capture::read_strain_movie(strain);
  const fs::path out = dir.path() / "movie.h5";
  const auto beyond = std::to_string(m.camera_frame_count + 100);
  const auto r = run_tactile("map " + strain.string() + " --strain accumulated --reference-frame " +
                             beyond + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("--reference-frame: frame " + beyond + " is not in " + strain.string() +
                        ", whose frames are 0 to " + std::to_string(m.camera_frame_count - 1)));
  EXPECT_FALSE(fs::exists(out));
  // The last frame is one it has.
  const auto last =
      run_tactile("map " + strain.string() + " --strain accumulated " + "--reference-frame " +
                  std::to_string(m.camera_frame_count - 1) + " --out " + out.string());
  EXPECT_THAT(last.output, Not(HasSubstr("is not in"))) << last.output;
}

// Options that cannot mean anything together are refused naming both, not taken silently.
TEST(Cli, OptionsThatContradictEachOtherAreUsageErrors) {
  const tactile::test::TempDir dir("contradict");
  const std::string movie = (demo_dir() / "movie.h5").string();
  auto r = run_tactile("play " + movie + " --headless --latero 127.0.0.1:9");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--headless: not with --latero"));
  const fs::path out = dir.path() / "perceive";
  r = run_tactile("perceive --out " + out.string() + " --trials 2 --export-trials 3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--export-trials requires --export-recordings"));
  EXPECT_FALSE(fs::exists(out));
}

// An empty path was taken as no file at all: `view --screenshot ''` opened the window and waited
// for a person to close it. Every option that takes a value refuses "" when it is parsed, in
// bounded time and before any work.
TEST(Cli, EmptyValuesAreUsageErrorsAtParseTime) {
  const tactile::test::TempDir d_tmp("empty");
  const fs::path& d = d_tmp.path();
  const std::string movie = (tactile::test::demo_dir() / "movie.h5").string();
  const std::string strain = (tactile::test::demo_dir() / "strain.h5").string();
  tactile::test::Started view({"view", movie, "--screenshot", ""}, d / "view.log");
  const auto ended = view.wait(30);
  ASSERT_TRUE(ended.ended) << "view --screenshot '' still running after 30 s";
  EXPECT_EQ(ended.exit_code, 2);
  std::ifstream log(d / "view.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("--screenshot: is empty"));
  for (const std::string& args :
       {"map " + strain + " --out ''", "map " + strain + " --out x.h5 --csv ''",
        "play " + movie + " --preview ''", "play " + movie + " --latero ''",
        "export " + movie + " --hjif ''", "capture " + d.string() + " --px-per-mm 47 --out ''"}) {
    const auto r = run_tactile(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("empty")) << args;
  }
  // A file that must exist: refused as missing, still at parse time.
  EXPECT_EQ(run_tactile("info ''").exit_code, 2);
  EXPECT_EQ(run_tactile("view " + movie + " --strain ''").exit_code, 2);
  EXPECT_FALSE(fs::exists(d / "x.h5"));
}

// A single image where a folder of frames is expected is the wrong kind of input: a usage
// error (2) naming it, like a value out of range, not a failure of the work (1).
TEST(Cli, ASingleImageWhereAFolderOfFramesIsExpectedIsAUsageError) {
  const tactile::test::TempDir d_tmp("single");
  const fs::path& d = d_tmp.path();
  const fs::path image = tactile::test::demo_dir() / "frames" / "frame_000.png";
  const auto r =
      run_tactile("capture " + image.string() + " --px-per-mm 47 --out " + (d / "s.h5").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is a single file, not a folder of frames"));
  EXPECT_FALSE(fs::exists(d / "s.h5"));
  // The same for a live session, which takes a folder of frames or a video as a rehearsal.
  const auto live =
      run_tactile("live " + image.string() + " --px-per-mm 47 --headless --seconds 1");
  EXPECT_EQ(live.exit_code, 2) << live.output;
  EXPECT_THAT(live.output,
              HasSubstr("is a single file, not a camera, a stream, a video or a folder"));
}

// `info` said 2077 frames and `play` 2147 for the same movie (the played output holds the
// ramps): every command counts the movie's own frames, and the ramps apart.
TEST(Cli, InfoAndPlayCountTheMovieFramesAlike) {
  const tactile::test::TempDir d_tmp("count");
  const fs::path movie = tactile::test::demo_dir() / "movie.h5";
  const std::string frames =
      std::to_string(tactile::movie::read_tactile_movie(movie).frame_count) + " movie frames";
  const auto info = run_tactile("info " + movie.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_THAT(info.output, HasSubstr("length      " + frames + " at "));
  const auto play = run_tactile("play " + movie.string() + " --headless --preview " +
                                (d_tmp.path() / "p.png").string());
  ASSERT_EQ(play.exit_code, 0) << play.output;
  EXPECT_THAT(play.output, HasSubstr("(of " + frames + " + "));
  EXPECT_THAT(play.output, HasSubstr("length      " + frames + " + "));
  EXPECT_THAT(play.output, HasSubstr(" frames of ramp from and to rest at "));
}
