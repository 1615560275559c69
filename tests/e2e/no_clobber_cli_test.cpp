// No command writes over its own input: every output path that is an input, the same path or a
// symbolic or hard link to it, or a folder output that would write one of its names onto an
// input, is refused as wrong usage (exit 2) naming both, and the input is left byte for byte as
// it was.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

const fs::path kDemo = tactile::test::demo_dir();
const fs::path kPrints = tactile::test::test_data("polyu-hrf-pores");
const fs::path kRecordings = tactile::test::test_data("biotac-slide");
const fs::path kMaterials = tactile::test::test_data("biotac-materials");

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string replaced(std::string command, const std::string& out) {
  const auto at = command.find("OUT");
  if (at != std::string::npos) command.replace(at, 3, out);
  return command;
}

class NoClobber : public ::testing::Test {
 protected:
  // A copy of `from` at dir_/to (folders made as needed).
  fs::path copy(const fs::path& from, const fs::path& to) const {
    EXPECT_TRUE(fs::exists(from)) << from;
    fs::create_directories((dir_ / to).parent_path());
    fs::copy_file(from, dir_ / to, fs::copy_options::overwrite_existing);
    return dir_ / to;
  }

  // Runs `command`, its OUT replaced by an output path that reaches `input`: the input's own
  // path, a symbolic link to it and a hard link to it. `written` is empty for a file output;
  // for a folder output it is the name the command writes inside the folder (the input is
  // then at FOLDER/written, and the links are made at OTHER/written). Each run must exit 2,
  // name `option` and the input, and leave the input as it was.
  void expect_refused(const std::string& command, const fs::path& input, const std::string& option,
                      const fs::path& written = {}) {
    const std::string before = bytes(input);
    ASSERT_FALSE(before.empty()) << input;
    const fs::path folder_of_input =
        written.empty()
            ? fs::path()
            : fs::path(input.string().substr(0, input.string().size() - written.string().size()));
    for (const char* how : {"same path", "symbolic link", "hard link"}) {
      fs::path out = written.empty() ? input : folder_of_input;
      if (std::string(how) != "same path") {
        const fs::path base = dir_ / ("link" + std::to_string(links_++));
        const fs::path link = written.empty() ? base / input.filename() : base / written;
        fs::create_directories(link.parent_path());
        if (std::string(how) == "symbolic link") {
          fs::create_symlink(input, link);
        } else {
          fs::create_hard_link(input, link);
        }
        out = written.empty() ? link : base;
      }
      const auto r = run_tactile(replaced(command, out.string()));
      EXPECT_EQ(r.exit_code, 2) << how << ": " << r.output;
      EXPECT_THAT(r.output, HasSubstr(option + " " + out.string())) << how;
      EXPECT_THAT(r.output, HasSubstr("would write over the input")) << how;
      EXPECT_THAT(r.output, HasSubstr(input.string())) << how;
      EXPECT_EQ(bytes(input), before) << how << ": the input changed";
    }
  }

  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
  int links_ = 0;  // folders of links made so far
};

TEST_F(NoClobber, Calibrate) {
  const auto grid = copy(kDemo / "frames" / "calibration" / "dot_grid.png", "grid.png");
  expect_refused("calibrate " + grid.string() + " --out OUT", grid, "--out");
}

TEST_F(NoClobber, Features) {
  const auto image = copy(kPrints / "image_01.jpg", "image_01.jpg");
  expect_refused("features " + image.string() + " --px-per-mm 47 --csv OUT", image, "--csv");
  const auto calib = copy(kDemo / "calibration.json", "calibration.json");
  expect_refused("features " + image.string() + " --calib " + calib.string() + " --csv OUT", calib,
                 "--csv");
}

TEST_F(NoClobber, Capture) {
  for (const char* f : {"frame_000.png", "frame_001.png", "frame_002.png"}) {
    copy(kDemo / "frames" / f, fs::path("seq") / f);
  }
  const auto frame = dir_ / "seq" / "frame_001.png";
  const std::string capture = "capture " + (dir_ / "seq").string() + " --px-per-mm 62 ";
  expect_refused(capture + "--out OUT", frame, "--out");
  // Frames named like the strain maps, and the maps drawn into their folder (or a link to it).
  for (const char* f : {"strain_000.png", "strain_001.png", "strain_002.png"}) {
    copy(kDemo / "frames" / "frame_000.png", fs::path("maps") / f);
  }
  expect_refused("capture " + (dir_ / "maps").string() + " --px-per-mm 62 --out " +
                     (dir_ / "s.h5").string() + " --maps OUT",
                 dir_ / "maps" / "strain_000.png", "--maps", "strain_000.png");
  // A calibration file named like one of the CSV files.
  const auto calib = copy(kDemo / "calibration.json", "calib/tracks.csv");
  expect_refused("capture " + (dir_ / "seq").string() + " --calib " + calib.string() + " --out " +
                     (dir_ / "s.h5").string() + " --csv OUT",
                 calib, "--csv", "tracks.csv");
  EXPECT_FALSE(fs::exists(dir_ / "s.h5"));
}

TEST_F(NoClobber, CaptureWritesNewNamesIntoItsInputFolder) {
  for (const char* f : {"frame_000.png", "frame_001.png", "frame_002.png"}) {
    copy(kDemo / "frames" / f, fs::path("seq") / f);
  }
  const std::string before = bytes(dir_ / "seq" / "frame_000.png");
  const auto seq = (dir_ / "seq").string();
  const auto r = run_tactile("capture " + seq + " --px-per-mm 62 --min-track 2 --out " + seq +
                             "/strain.h5 --csv " + seq);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "seq" / "tracks.csv"));
  EXPECT_EQ(bytes(dir_ / "seq" / "frame_000.png"), before);
}

// Found by the second hostile-input run: strain maps drawn into the frames folder became frames
// of the next capture of it.
TEST_F(NoClobber, CaptureDrawsNoMapsAmongItsFrames) {
  for (const char* f : {"frame_000.png", "frame_001.png", "frame_002.png"}) {
    copy(kDemo / "frames" / f, fs::path("seq") / f);
  }
  const auto seq = (dir_ / "seq").string();
  for (const std::string& maps : {seq, seq + "/.", seq + "/../seq"}) {
    const auto r = run_tactile("capture " + seq + " --px-per-mm 62 --min-track 2 --out " +
                               (dir_ / "s.h5").string() + " --maps " + maps);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("--maps " + maps + " is the frames folder IMAGE_DIR"));
    EXPECT_FALSE(fs::exists(dir_ / "seq" / "strain_000.png")) << maps;
    EXPECT_FALSE(fs::exists(dir_ / "s.h5")) << maps;
  }
}

TEST_F(NoClobber, TrainPores) {
  copy(kPrints / "image_01.jpg", "prints/image_01.jpg");
  const auto marks = copy(kPrints / "pores_01.txt", "prints/pores_01.txt");
  expect_refused("train-pores --prints " + (dir_ / "prints").string() + " --px-per-mm 47 --out OUT",
                 marks, "--out");
}

TEST_F(NoClobber, Evaluate) {
  const auto seq = dir_ / "seq";
  copy(kDemo / "frames" / "scene.json", "seq/scene.json");
  const auto landmarks = copy(kDemo / "frames" / "landmarks.csv", "seq/landmarks.csv");
  const auto strain = copy(kDemo / "strain.h5", "csv/evaluation_summary.csv");
  expect_refused("evaluate " + seq.string() + " " + strain.string() + " --csv OUT", strain, "--csv",
                 "evaluation_summary.csv");
  // The ground truth, linked into the CSV folder under a name the command writes.
  fs::create_directories(dir_ / "csv2");
  fs::create_symlink(landmarks, dir_ / "csv2" / "evaluation_frames.csv");
  const auto r = run_tactile("evaluate " + seq.string() + " " + strain.string() + " --csv " +
                             (dir_ / "csv2").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("input SEQ_DIR " + landmarks.string()));
}

TEST_F(NoClobber, Map) {
  const auto strain = copy(kDemo / "strain.h5", "S.h5");
  expect_refused("map " + strain.string() + " --out OUT", strain, "--out");
  expect_refused("map " + strain.string() + " --out " + (dir_ / "m.h5").string() + " --csv OUT",
                 strain, "--csv");
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
  // Two outputs on one file: the second would replace the first.
  const auto r = run_tactile("map " + strain.string() + " --out " + (dir_ / "m.h5").string() +
                             " --csv " + (dir_ / "m.h5").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("would write the same file"));
}

TEST_F(NoClobber, Experiment) {
  const auto source = copy(kDemo / "strain.h5", "results/movies/source.h5");
  const auto exp = dir_ / "exp.json";
  std::ofstream(exp) << R"({"name": "noclobber", "seed": 1, "sources": [{"name": "s", "file": ")"
                     << source.string()
                     << R"("}], "layouts": ["stress"], "methods": ["proportional"]})";
  expect_refused("experiment " + exp.string() + " --out OUT", source, "--out", "movies/source.h5");
  // The experiment file itself, where the experiment copies its input.
  fs::copy_file(exp, dir_ / "results" / "experiment.json");
  expect_refused("experiment " + (dir_ / "results" / "experiment.json").string() + " --out OUT",
                 dir_ / "results" / "experiment.json", "--out", "experiment.json");
}

TEST_F(NoClobber, PerceiveRecordings) {
  const auto rec = copy(kRecordings / "mat1_2_bio.csv", "rec/mat1_2_bio.csv");
  const std::string before = bytes(rec);
  const std::string perceive = "perceive --recordings " + (dir_ / "rec").string() + " --out ";
  // The output folder is an input file.
  auto r = run_tactile(perceive + rec.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("would write over the input --recordings " + rec.string()));
  // recordings.csv in the output folder is a link to a recording.
  for (const char* how : {"symbolic", "hard"}) {
    const auto out = dir_ / (std::string(how) + "-out");
    fs::create_directories(out);
    if (std::string(how) == "symbolic") {
      fs::create_symlink(rec, out / "recordings.csv");
    } else {
      fs::create_hard_link(rec, out / "recordings.csv");
    }
    r = run_tactile(perceive + out.string());
    EXPECT_EQ(r.exit_code, 2) << how << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(std::string("through a ") + how + " link")) << how;
    EXPECT_EQ(bytes(rec), before) << how;
  }
}

// Found by the second hostile-input run: `synth` of 4 frames into the folder of an earlier run of
// 12 left frame_004..frame_011 there, and `capture` then read one sequence of both runs.
TEST_F(NoClobber, SynthRefusesAFolderWithFramesItWouldNotReplace) {
  const auto out = dir_ / "seq";
  for (const char* f : {"frame_000.png", "frame_001.png", "frame_002.png", "frame_003.png"}) {
    copy(kDemo / "frames" / f, fs::path("seq") / f);
  }
  const std::string last = bytes(out / "frame_003.png");
  auto r = run_tactile("synth " + out.string() + " --frames 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("already holds 2 image file(s) this run of 2 frames would not "
                                  "replace (frame_002.png .. frame_003.png)"));
  EXPECT_EQ(bytes(out / "frame_003.png"), last);
  EXPECT_FALSE(fs::exists(out / "landmarks.csv"));
  r = run_tactile("synth " + out.string() + " --frames 2 --from-print " +
                  (kPrints / "image_01.jpg").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("would not replace"));
  // Frames it does replace are no obstacle: a rerun of the same length works.
  fs::remove(out / "frame_002.png");
  fs::remove(out / "frame_003.png");
  r = run_tactile("synth " + out.string() + " --frames 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// Found by the third hostile-input run: `demo --keep` of 3 frames into the folder of an earlier
// demo of 5 left frame_003 and frame_004 in its frames folder, mixing the two runs. Refused as
// `synth` refuses, before any work.
TEST_F(NoClobber, DemoRefusesAFramesFolderWithFramesItWouldNotReplace) {
  const auto out = dir_ / "demo";
  for (const char* f :
       {"frame_000.png", "frame_001.png", "frame_002.png", "frame_003.png", "frame_004.png"}) {
    copy(kDemo / "frames" / f, fs::path("demo/frames") / f);
  }
  const std::string last = bytes(out / "frames" / "frame_004.png");
  auto r = run_tactile("demo --headless --keep --frames 3 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--out " + out.string() + ": its frames folder " +
                                  (out / "frames").string() +
                                  " already holds 2 image file(s) this run of 3 frames would not "
                                  "replace (frame_003.png .. frame_004.png)"));
  EXPECT_EQ(bytes(out / "frames" / "frame_004.png"), last);
  for (const char* written : {"calibration.json", "strain.h5", "movie.h5", "frames/scene.json"}) {
    EXPECT_FALSE(fs::exists(out / written)) << written;
  }
  // Without --keep no frame is written: the old ones are no obstacle.
  r = run_tactile("demo --headless --frames 3 --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// Folder outputs given as a file: a usage error naming the option before any work, the file
// left as it was (before, demo, synth and perceive ended with the standard library's
// "filesystem error: cannot create directories").
TEST_F(NoClobber, AFolderOutputThatIsAFileIsRefusedBeforeTheWork) {
  const auto file = dir_ / "a-file";
  std::ofstream(file) << "kept\n";
  for (const std::string& command :
       {"demo --out " + file.string(), "synth " + file.string() + " --frames 2",
        "perceive --out " + file.string()}) {
    const auto r = run_tactile(command);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(file.string() + ": is a file, not a folder")) << command;
    EXPECT_THAT(r.output, ::testing::Not(HasSubstr("filesystem error"))) << command;
    EXPECT_EQ(bytes(file), "kept\n") << command;
  }
}

// Found by the second hostile-input run: when no recording could be analysed, perceive replaced
// the recordings.csv of an earlier run by an empty table.
TEST_F(NoClobber, PerceiveOfNoReadableRecordingKeepsTheOldTable) {
  fs::create_directories(dir_ / "rec");
  std::ofstream(dir_ / "rec" / "broken_bio.csv") << "not,a,recording\n";
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "recordings.csv") << "an earlier table\n";
  const auto r = run_tactile("perceive --recordings " + (dir_ / "rec").string() + " --out " +
                             (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("none of the 1 recordings could be analysed"));
  EXPECT_THAT(r.output, HasSubstr("broken_bio.csv"));
  EXPECT_EQ(bytes(dir_ / "out" / "recordings.csv"), "an earlier table\n");
}

TEST_F(NoClobber, ClassifyTrain) {
  const auto labels = dir_ / "labels.csv";
  std::ofstream(labels) << "file,class\nmat1_1_bio.csv,mat1\nmat7_1_bio.csv,mat7\n";
  const std::string train = "classify train --recordings ";
  expect_refused(train + kMaterials.string() + " --labels " + labels.string() + " --out OUT",
                 labels, "--out");
  const auto rec = copy(kMaterials / "mat1_1_bio.csv", "rec/mat1_1_bio.csv");
  copy(kMaterials / "mat7_1_bio.csv", "rec/mat7_1_bio.csv");
  expect_refused(train + (dir_ / "rec").string() + " --labels " + labels.string() + " --out OUT",
                 rec, "--out");
}

TEST_F(NoClobber, ClassifyTest) {
  const auto model = dir_ / "model.json";
  std::ofstream(model) << "{}";
  // The labels file in the CSV folder, named like a file the command writes there.
  const auto labels = dir_ / "csv" / "predictions.csv";
  fs::create_directories(labels.parent_path());
  std::ofstream(labels) << "file,class\nmat1_1_bio.csv,mat1\nmat7_1_bio.csv,mat7\n";
  const std::string test = "classify test --model " + model.string() + " --recordings ";
  expect_refused(test + kMaterials.string() + " --labels " + labels.string() + " --csv OUT", labels,
                 "--csv", "predictions.csv");
  // A recording named like one, the CSV folder being the recordings folder.
  const auto rec = copy(kMaterials / "mat1_1_bio.csv", "rec/confusion.csv");
  expect_refused(test + (dir_ / "rec").string() + " --labels " + labels.string() + " --csv OUT",
                 rec, "--csv", "confusion.csv");
  // The model itself.
  const auto model_in_csv = copy(model, "csv2/confusion.svg");
  expect_refused("classify test --model " + model_in_csv.string() + " --recordings " +
                     kMaterials.string() + " --labels " + labels.string() + " --csv OUT",
                 model_in_csv, "--csv", "confusion.svg");
}

TEST_F(NoClobber, PlayPreview) {
  const auto movie = copy(kDemo / "movie.h5", "movie.h5");
  expect_refused("play --headless " + movie.string() + " --preview OUT", movie, "--preview");
}

TEST_F(NoClobber, ViewScreenshot) {
  const auto movie = copy(kDemo / "movie.h5", "movie.h5");
  expect_refused("view " + movie.string() + " --no-strain --screenshot OUT", movie, "--screenshot");
  const auto strain = copy(kDemo / "strain.h5", "strain.h5");
  expect_refused("view " + movie.string() + " --strain " + strain.string() + " --screenshot OUT",
                 strain, "--screenshot");
}

}  // namespace
