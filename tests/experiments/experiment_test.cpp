// Experiments: a small grid runs and writes its folder reproducibly; every bad experiment file is
// refused by name before any work.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../common/file_text.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::experiments {
namespace {

using namespace tactile::capture;
using namespace tactile::mapping;
using namespace tactile::perception;

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// Ground truth of a short bump scene on a coarse grid: fast enough for debug+sanitizer builds.
const char* kSmall = R"({
  "name": "small", "seed": 3,
  "sources": [{"name": "bump", "ground_truth": {"scene": "bump", "frames": 12}, "grid_spacing_mm": 0.5}],
  "layouts": ["stress", "latero"],
  "methods": ["proportional", "integrated"],
  "parameters": {"strain": ["per-frame", "accumulated"], "rate_hz": 200}
})";

std::string slurp(const fs::path& path) {
  return tactile::test::file_text(path);
}

// The CSV without its first line (which carries the creation time).
std::string table_of(const fs::path& csv) {
  const auto text = slurp(csv);
  return text.substr(text.find('\n') + 1);
}

TEST(Experiment, ParsesTheGridInAFixedOrder) {
  const auto ex = parse_experiment(kSmall, "small.json", ".");
  EXPECT_EQ(ex.name, "small");
  EXPECT_EQ(ex.seed, 3u);
  ASSERT_EQ(ex.runs.size(), 1u * 2 * 2 * 2);
  EXPECT_EQ(ex.runs[0].id, "000-bump-stress-proportional-per-frame");
  EXPECT_EQ(ex.runs[1].id, "001-bump-stress-proportional-accumulated");
  EXPECT_EQ(ex.runs[7].id, "007-bump-latero-integrated-accumulated");
  EXPECT_DOUBLE_EQ(ex.runs[5].params.rate_hz.value(), 200);
  EXPECT_EQ(ex.sources[0].scene.seed, 3u);  // experiment seed + source index
  EXPECT_EQ(ex.sources[0].scene.frame_count, 12);
}

// Two runs that differed only in normalisation had the same name (and so wrote the same movie
// file): a run is named by every parameter that varies, and the grid is stated whole.
TEST(Experiment, RunsAreNamedByEveryParameterThatVaries) {
  const auto ex = parse_experiment(R"({
    "name": "norms", "seed": 1,
    "sources": [{"name": "bump", "ground_truth": {"scene": "bump", "frames": 12}}],
    "layouts": ["stress"],
    "methods": ["integrated"],
    "parameters": {"normalisation": ["none", "peak"], "gain_um_per_strain": [500, 1000],
                   "rate_hz": 200}
  })",
                                   "norms.json", ".");
  ASSERT_EQ(ex.runs.size(), 4u);
  std::set<std::string> ids;
  for (const auto& run : ex.runs) ids.insert(run.id);
  EXPECT_EQ(ids.size(), 4u);
  EXPECT_EQ(ex.runs[0].id,
            "000-bump-stress-integrated-per-frame-gain_um_per_strain-500-normalisation-none");
  EXPECT_EQ(ex.runs[3].id,
            "003-bump-stress-integrated-per-frame-gain_um_per_strain-1000-normalisation-peak");
  EXPECT_EQ(ex.grid,
            "1 sources x 1 layouts x 1 methods x 4 parameter sets (layouts: stress; methods: "
            "integrated; gain_um_per_strain: 500, 1000; normalisation: none, peak)");
  // A parameter given one value names no run.
  for (const auto& run : ex.runs) EXPECT_THAT(run.id, Not(HasSubstr("rate_hz")));
}

TEST(Experiment, WithoutARateEachLayoutMapsAtItsOwnRateAsTactileMap) {
  // The rate `tactile map --layout X` uses when --rate-hz is not given: the layout's own.
  const auto ex = parse_experiment(R"({
    "name": "rates", "seed": 1,
    "sources": [{"name": "bump", "ground_truth": {"scene": "bump", "frames": 12}}],
    "layouts": ["stress", "latero"],
    "methods": ["proportional"]
  })",
                                   "rates.json", ".");
  ASSERT_EQ(ex.runs.size(), 2u);
  EXPECT_EQ(ex.runs[1].id, "001-bump-latero-proportional-per-frame");
  EXPECT_DOUBLE_EQ(ex.runs[0].params.rate_hz.value(), 700);
  EXPECT_DOUBLE_EQ(ex.runs[1].params.rate_hz.value(), 750);
}

TEST(Experiment, RefusesARateNoDeviceCanPlayBeforeAnyWork) {
  try {
    (void)parse_experiment(R"({
      "name": "half", "seed": 1, "sources": [{"name": "bump", "ground_truth": {"scene": "bump"}}],
      "layouts": ["stress"], "methods": ["proportional"], "parameters": {"rate_hz": 500.5}
    })",
                           "half.json", ".");
    ADD_FAILURE() << "a 500.5 Hz experiment was accepted";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), HasSubstr("500.5 Hz is not playable: devices play a whole number"));
  }
}

TEST(Experiment, WritesItsFolderTheSameWayOnOneOrTwoThreads) {
  const tactile::test::TempDir one_tmp("one");
  const std::filesystem::path& one = one_tmp.path();
  const tactile::test::TempDir two_tmp("two");
  const std::filesystem::path& two = two_tmp.path();
  const auto report = run_experiment(parse_experiment(kSmall, "small.json", "."), one, 1);
  run_experiment(parse_experiment(kSmall, "small.json", "."), two, 2);
  for (const char* f :
       {"experiment.json", "resolved.json", "metrics.csv", "plots/correlation.png",
        "plots/saturation.png", "plots/activity-bump-stress.png", "plots/activity-bump-latero.png",
        "plots/correlation.svg", "plots/activity-bump-latero.svg",
        "movies/003-bump-stress-integrated-accumulated.h5"}) {
    EXPECT_TRUE(fs::exists(one / f)) << f;
  }
  EXPECT_EQ(slurp(one / "experiment.json"), kSmall);
  EXPECT_THAT(slurp(one / "metrics.csv"), HasSubstr("# made by tactile"));
  EXPECT_THAT(slurp(one / "resolved.json"), HasSubstr("\"normalisation_factor\""));
  EXPECT_EQ(table_of(one / "metrics.csv").find("map_ms"),
            table_of(two / "metrics.csv").find("map_ms"));
  // Same numbers whatever the thread count (the timing column aside).
  const auto strip_timing = [](std::string table) {
    std::istringstream in(table);
    std::string line, out;
    while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  EXPECT_EQ(strip_timing(table_of(one / "metrics.csv")),
            strip_timing(table_of(two / "metrics.csv")));
  const auto a = movie::read_tactile_movie(one / "movies/002-bump-stress-integrated-per-frame.h5");
  const auto b = movie::read_tactile_movie(two / "movies/002-bump-stress-integrated-per-frame.h5");
  EXPECT_EQ(a.deflection_um, b.deflection_um);
  // Made from the experiment file; its name, the run and the source are with the parameters.
  EXPECT_EQ(a.provenance.input, "small.json");
  EXPECT_THAT(a.provenance.parameters_json, HasSubstr("\"experiment\":\"small\""));
  EXPECT_THAT(a.provenance.parameters_json,
              HasSubstr("\"run\":\"002-bump-stress-integrated-per-frame\""));
  EXPECT_THAT(a.provenance.parameters_json, HasSubstr("\"source\":\"bump\""));
  EXPECT_EQ(a.provenance.command_line, "");
  EXPECT_THAT(a.provenance.parameters_json, HasSubstr("\"strain\":\"per-frame\""));
  EXPECT_EQ(a.provenance.method, "integrated");
  // 11 strain frames at 60 Hz (1/60 .. 11/60 s) at 200 Hz: floor(10/60 * 200) + 1 frames.
  EXPECT_EQ(a.frame_count, 34);
  ASSERT_EQ(report.results.size(), 8u);
  EXPECT_GT(report.results[2].metrics.compared_pairs, 0);
  // experiment_output names every file written, so that no input can be among them unnoticed.
  const Output output = experiment_output("--out", one);
  for (const auto& file : report.files) {
    const fs::path relative = fs::path(file).lexically_relative(one);
    const bool named =
        std::find(output.files.begin(), output.files.end(), relative) != output.files.end() ||
        std::find(output.subfolders.begin(), output.subfolders.end(), *relative.begin()) !=
            output.subfolders.end();
    EXPECT_TRUE(named) << file;
  }
}

void refused(const std::string& text, const std::string& message,
             const fs::path& base = fs::temp_directory_path()) {
  try {
    parse_experiment(text, "bad.json", base);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json")) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(message)) << e.what();
  }
}

std::string edit(const std::string& from, const std::string& to) {
  std::string text = kSmall;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Experiment, RefusesBadFilesBeforeAnyWork) {
  refused("{", "not valid JSON");
  refused("[]", "must be a JSON object");
  refused(edit("\"name\": \"small\", ", ""), "missing field 'name'");
  refused(edit("\"seed\": 3,", ""), "missing field 'seed'");
  refused(edit("\"layouts\": [\"stress\", \"latero\"],", ""), "missing field 'layouts'");
  refused(edit("\"methods\": [\"proportional\", \"integrated\"],", ""), "missing field 'methods'");
  refused(edit("\"seed\": 3", "\"seed\": 3, \"sead\": 4"), "unknown field 'sead'");
  refused(edit("\"integrated\"]", "\"integrated\", \"wavelet\"]"),
          "unknown method 'wavelet' (known: proportional, integrated, profile)");
  refused(edit("[\"proportional\", \"integrated\"]", "[]"), "'methods' must be a non-empty list");
  refused(edit("[\"stress\", \"latero\"]", "[]"), "'layouts' must be a non-empty list");
  refused(edit("\"latero\"]", "\"braille\"]"), "unknown layout 'braille'");
  refused(edit("\"latero\"]", "\"missing-layout.json\"]"), "cannot open layout file");
  refused(edit("\"accumulated\"]", "\"integral\"]"),
          "parameters.strain: unknown strain 'integral' (known: per-frame, accumulated)");
  refused(edit("\"rate_hz\": 200", "\"rate_hz\": 800"),
          "rate 800 Hz is above layout 'stress' maximum rate 700 Hz");
  refused(edit("\"rate_hz\": 200", "\"rate_hz\": -1"),
          "parameters.rate_hz -1 is out of range: must be from 1 to 65535");
  refused(edit("\"rate_hz\": 200", "\"gain\": 2"), "unknown field 'gain'");
  refused(edit("\"frames\": 12}", "\"frames\": 12, \"frame_rate_hz\": 900}"),
          "source 'bump' runs at 900 Hz, faster than layout 'stress' can play (700 Hz");
  refused(edit("\"scene\": \"bump\"", "\"scene\": \"ridge\""),
          "sources[0].ground_truth.scene: unknown scene 'ridge' (known: bump, hole, flat-slide, "
          "flat-rotate, flat-stick-slip)");
  refused(edit("\"frames\": 12", "\"frames\": 1"), "frames = 1 is not in 2..100000");
  refused(edit("\"ground_truth\"", "\"groundtruth\""), "unknown field 'groundtruth'");
  refused(edit("\"name\": \"bump\", ", "\"name\": \"bump\", \"file\": \"x.h5\", "),
          "needs exactly one of 'file', 'synthetic', 'ground_truth'");
  refused(edit("\"name\": \"bump\"", "\"name\": \"bump/1\""),
          "sources[0].name \"bump/1\" is not a plain name: it holds '/'");
  refused(edit("\"name\": \"bump\", \"ground_truth\": {\"scene\": \"bump\", \"frames\": 12}, "
               "\"grid_spacing_mm\": 0.5",
               "\"name\": \"rec\", \"file\": \"no-such-movie.h5\""),
          "sources[0] ('rec')");
  const std::string source =
      R"({"name": "bump", "ground_truth": {"scene": "bump", "frames": 12}, "grid_spacing_mm": 0.5})";
  refused(edit(source, source + ", " + source), "two sources are named 'bump'");
  refused(edit("\"grid_spacing_mm\": 0.5", "\"grid_spacing_mm\": 0"),
          "grid_spacing_mm = 0 is not in [0.05, 5]");
  // Found by the second hostile-input run: a key given twice was read as its last value.
  refused(edit("\"seed\": 3,", "\"seed\": 3, \"seed\": 4,"), "field 'seed' appears twice");
  // No run accumulates strain, so a reference frame would change nothing.
  refused(edit("[\"per-frame\", \"accumulated\"]", "[\"per-frame\"], \"reference_frame\": 5"),
          "parameters.reference_frame is used only by strain 'accumulated', and no run has it");
  EXPECT_NO_THROW(parse_experiment(
      edit("\"accumulated\"]", "\"accumulated\"], \"reference_frame\": 5"), "ok.json", "."));
}

// Each name of the file becomes part of a path (the default output folder NAME-results, the
// movies and plots named after source and layout) or a line of the manifest: one that is not a
// single plain file name is refused naming its field, before any work.
TEST(Experiment, RefusesNamesThatAreNotPlainFileNames) {
  refused(edit("\"name\": \"small\"", "\"name\": \"../escape\""),
          "name \"../escape\" is not a plain name: it holds '/'");
  refused(edit("\"name\": \"small\"", "\"name\": \"/tmp/escape\""),
          "name \"/tmp/escape\" is not a plain name");
  refused(edit("\"name\": \"small\"", "\"name\": \"..\""), "name \"..\" is not a plain name");
  refused(edit("\"name\": \"small\"", "\"name\": \"a\\nb\""),
          "name \"a\\nb\" is not a plain name: it holds a control character");
  refused(edit("\"name\": \"small\"", "\"name\": \"a b\""), "name \"a b\" is not a plain name");
  refused(edit("\"name\": \"bump\"", "\"name\": \"..\""),
          "sources[0].name \"..\" is not a plain name");
  refused(edit("\"name\": \"bump\"", "\"name\": \".\""),
          "sources[0].name \".\" is not a plain name");
  refused(edit("\"name\": \"bump\"", "\"name\": \"../escape\""),
          "sources[0].name \"../escape\" is not a plain name");
  const std::string too_long(101, 's');
  refused(edit("\"name\": \"bump\"", "\"name\": \"" + too_long + "\""),
          "sources[0].name \"" + too_long + "\" is not a plain name: it is 101 bytes long");
  refused(edit("\"name\": \"small\"", "\"name\": \"" + too_long + "\""),
          "name \"" + too_long + "\" is not a plain name");
  // The longest name taken: both a source and a layout of it still make a run id and a plot
  // name shorter than a file name may be.
  const std::string longest(100, 's');
  EXPECT_NO_THROW(parse_experiment(edit("\"name\": \"bump\"", "\"name\": \"" + longest + "\""),
                                   "ok.json", "."));
}

// Found by the second hostile-input run: lists of 3000 and 8000 values (24 million runs) made
// the parse run for minutes; the count is refused before the product is built.
TEST(Experiment, RefusesMoreRunsThanTheLimitAtOnce) {
  std::string gains, fractions;
  for (int i = 1; i <= 3000; ++i) gains.append(i > 1 ? "," : "").append(std::to_string(i));
  for (int i = 1; i <= 8000; ++i)
    fractions.append(i > 1 ? "," : "").append(std::to_string(i / 10000.0));
  const auto t0 = std::chrono::steady_clock::now();
  refused(edit("\"rate_hz\": 200", "\"rate_hz\": 200, \"gain_um_per_strain\": [" + gains +
                                       "], \"peak_fraction\": [" + fractions + "]"),
          "the parameter lists make 24000000 runs, more than the limit of 100000");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10);
  // Within the limit per list but not in all: 1 source x 2 layouts x 2 methods x 30000 sets.
  std::string rates;
  for (int i = 0; i < 30000; ++i)
    rates.append(i > 0 ? "," : "").append(std::to_string(1 + i % 200));
  refused(edit("\"rate_hz\": 200", "\"rate_hz\": [" + rates + "]"),
          "1 sources x 2 layouts x 2 methods x 60000 parameter sets make 240000 runs");
}

// Numbers of a ground-truth scene and of the parameters: a value no camera, finger or display
// has is refused with the field and the range (those of `tactile synth` and `tactile map`).
TEST(Experiment, RefusesNumbersOutOfTheirRangeByField) {
  struct Case {
    const char* after;  // the field is added after this text of kSmall
    const char* field;
    const char* message;
  };
  const std::vector<Case> cases = {
      {"\"frames\": 12", "\"frame_rate_hz\": 1e300",
       "sources[0].ground_truth.frame_rate_hz 1e+300 is out of range: must be from 1 to 100000"},
      {"\"frames\": 12", "\"frame_rate_hz\": 0.5",
       "sources[0].ground_truth.frame_rate_hz 0.5 is out of range"},
      {"\"frames\": 12", "\"height_mm\": 1e9",
       "sources[0].ground_truth.height_mm 1000000000 is out of range: must be from 0 to 5"},
      {"\"frames\": 12", "\"width_mm\": 0.01",
       "sources[0].ground_truth.width_mm 0.01 is out of range: must be from 0.1 to 50"},
      {"\"frames\": 12", "\"contact_semi_x_mm\": 300",
       "sources[0].ground_truth.contact_semi_x_mm 300 is out of range: must be from 0.5 to 20"},
      {"\"frames\": 12", "\"speed_mm_per_s\": -3",
       "sources[0].ground_truth.speed_mm_per_s -3 is out of range: must be from 0 to 100"},
      {"\"frames\": 12", "\"noise\": 1000",
       "sources[0].ground_truth.noise 1000 is out of range: must be from 0 to 128"},
      {"\"frames\": 12", "\"frame_rate_hz\": 1e999", "not valid JSON"},
      {"\"rate_hz\": 200", "\"gain_um_per_strain\": 1e12",
       "parameters.gain_um_per_strain 1000000000000 is out of range: must be from -1000000 to "
       "1000000"},
      {"\"rate_hz\": 200", "\"peak_fraction\": 2",
       "parameters.peak_fraction 2 is out of range: must be from 0 to 1"},
      {"\"rate_hz\": 200", "\"min_triangle_quality\": -0.5",
       "parameters.min_triangle_quality -0.5 is out of range: must be from 0 to 1"},
      // Beyond a 32-bit frame number: once cast silently to another frame.
      {"\"rate_hz\": 200", "\"reference_frame\": 4294967296",
       "parameters.reference_frame 4294967296 is out of range: must be from -1 to 100000000"},
  };
  for (const auto& c : cases) {
    refused(edit(c.after, std::string(c.after) + ", " + c.field), c.message);
  }
}

TEST(Experiment, CustomLayoutFilesResolveFromTheExperimentsFolder) {
  const tactile::test::TempDir dir_tmp("layout");
  const std::filesystem::path& dir = dir_tmp.path();
  fs::create_directories(dir);
  std::ofstream(dir / "slow.json") << R"({"name": "slow", "rows": 4, "cols": 4,
    "pitch_mm": [1, 1], "contactor_size_mm": [0.5, 0.5], "deflection_axis": "x",
    "deflection_range_um": [-50, 50], "max_rate_hz": 100})";
  const auto text = edit("\"latero\"]", "\"slow.json\"]");
  // 200 Hz is too fast for the custom layout: incompatible layout and rate.
  refused(text, "rate 200 Hz is above layout 'slow' maximum rate 100 Hz", dir);
  std::string slower = text;
  slower.replace(slower.find("\"rate_hz\": 200"), 14, "\"rate_hz\": 100");
  const auto ok = parse_experiment(slower, "ok.json", dir);
  EXPECT_EQ(ok.layouts[1].name, "slow");
  EXPECT_EQ(ok.layouts[1].rows, 4);
  EXPECT_EQ(ok.layout_files, std::vector<fs::path>{dir / "slow.json"});
}

}  // namespace
}  // namespace tactile::experiments
