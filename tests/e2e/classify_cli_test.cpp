// `tactile classify` on the vendored real BioTac recordings of 4 materials: train, test,
// predict, cross-validation, and bad input (clear messages naming the file, exit codes).

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "../common/temp_dir.hpp"
#include "csv_rows.hpp"
#include "run.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/recording_csv.hpp"

using tactile::test::read_csv_rows;
using tactile::test::run_tactile;

namespace {

const std::string kMaterials = std::string(TACTILE_TEST_DATA_DIR) + "/biotac-materials";
constexpr const char* kClasses[] = {"mat1", "mat7", "mat14", "mat20"};

// Labels of the vendored recordings whose trial number is in `trials` (e.g. "12": 1 and 2).
std::string labels_of_trials(const std::filesystem::path& dir, const std::string& trials) {
  std::string text = "file,class\n";
  for (const char* m : kClasses)
    for (char t : trials) text += std::string(m) + "_" + t + "_bio.csv," + m + "\n";
  const auto path = dir / ("labels_" + trials + ".csv");
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

// Trained on trials 1-2, tested on 3-4: 8 held-out recordings of 4 materials, chance 1 in 4; 6
// or more right by chance has probability 0.004 (binomial), so the bound says it learned.
TEST(ClassifyCli, TrainTestPredictOnRealRecordings) {
  const tactile::test::TempDir dir_tmp("real");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto model = (dir / "model.json").string();
  const auto t = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             labels_of_trials(dir, "12") + " --out " + model + " --threads 2");
  ASSERT_EQ(t.exit_code, 0) << t.output;
  // The default of slides: pressure and 6 electrode clusters over two halves, 7 band powers.
  EXPECT_NE(t.output.find("8 recordings, 4 classes, 21 inputs"), std::string::npos) << t.output;
  const auto r =
      run_tactile("classify test --model " + model + " --recordings " + kMaterials + " --labels " +
                  labels_of_trials(dir, "34") + " --csv " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* c : kClasses)
    EXPECT_NE(("\n" + r.output).find(std::string("\n") + c + ": "), std::string::npos) << r.output;
  const auto at = r.output.find("accuracy ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const auto open = r.output.find('(', at), slash = r.output.find('/', at);
  const int correct = std::stoi(r.output.substr(open + 1, slash - open - 1));
  const int tested = std::stoi(r.output.substr(slash + 1));
  EXPECT_EQ(tested, 8);
  EXPECT_GE(correct, 6) << r.output;
  // Confusion matrix: header + one row per class, counts summing to the 8 tested; predictions:
  // one row per file, its `correct` column summing to the printed count.
  const auto confusion = read_csv_rows(dir / "out" / "confusion.csv");
  ASSERT_EQ(confusion.size(), 5u);
  int total = 0;
  for (std::size_t i = 1; i < confusion.size(); ++i)
    for (std::size_t j = 1; j < confusion[i].size(); ++j) total += std::stoi(confusion[i][j]);
  EXPECT_EQ(total, 8);
  const auto predictions = read_csv_rows(dir / "out" / "predictions.csv");
  ASSERT_EQ(predictions.size(), 9u);
  int right = 0;
  for (std::size_t i = 1; i < predictions.size(); ++i) right += std::stoi(predictions[i][3]);
  EXPECT_EQ(right, correct);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "confusion.svg"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "confusion.png"));
  // predict: one line per file, naming one of the model's classes.
  const auto p = run_tactile("classify predict --model " + model + " " + kMaterials +
                             "/mat7_4_bio.csv " + kMaterials + "/mat20_3_bio.csv");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  for (const char* f : {"mat7_4_bio.csv: mat", "mat20_3_bio.csv: mat"})
    EXPECT_NE(p.output.find(f), std::string::npos) << p.output;
}

TEST(ClassifyCli, CrossValidationReportsMeanAndSpread) {
  const tactile::test::TempDir dir_tmp("cv");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto r = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             kMaterials + "/labels.csv --out " + (dir / "m.json").string() +
                             " --cv 4 --kernel-degree 2 --inputs means,bands --c 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cross-validation (4 folds, stratified): accuracy "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("pooled "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("16 recordings, 4 classes, 21 inputs"), std::string::npos) << r.output;
  // Baseline, electrodes and trim are the slide defaults, chosen on the project's recordings:
  // the report says so and names the nested command.
  EXPECT_NE(r.output.find("plain cross-validation of fixed options. The stroke defaults were "
                          "chosen by nested cross-validation"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("`classify train --select --cv 4`"), std::string::npos) << r.output;
  // Every option named: nothing was chosen on the project's recordings, no such note.
  const auto all = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                               kMaterials + "/labels.csv --out " + (dir / "m2.json").string() +
                               " --cv 4 --kernel-degree 1 --inputs stats --c 1 --baseline-at "
                               "none --electrodes each --trim 0");
  ASSERT_EQ(all.exit_code, 0) << all.output;
  EXPECT_NE(all.output.find("cross-validation (4 folds, stratified): accuracy "), std::string::npos)
      << all.output;
  EXPECT_EQ(all.output.find("stroke defaults"), std::string::npos) << all.output;
}

// --select with --cv: the nested figure (every recording tested once by an outer fold), each
// fold's choice, the choice on all recordings, and a model file that records it; options the
// user names are not searched.
TEST(ClassifyCli, SelectReportsNestedCrossValidationAndRecordsTheChoice) {
  const tactile::test::TempDir dir_tmp("select");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto r = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             kMaterials + "/labels.csv --out " + (dir / "m.json").string() +
                             " --cv 4 --select --trim 0.1 --kernel-degree 1 --baseline-at none");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // 5 input sets x 2 electrode signals x 6 values of C.
  EXPECT_NE(r.output.find("nested cross-validation (4 outer folds, stratified; options chosen in "
                          "each by up to 5-fold cross-validation of its training rows among 60 "
                          "candidates): accuracy "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("pooled "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/16\n"), std::string::npos) << r.output;
  for (const char* fold : {"  fold 1 chose ", "  fold 4 chose "})
    EXPECT_NE(r.output.find(fold), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("classify train --select: 16 recordings, 4 classes; chose "),
            std::string::npos)
      << r.output;
  const auto model = tactile::perception::read_classifier_model(dir / "m.json");
  ASSERT_TRUE(model.selection.has_value());
  ASSERT_EQ(model.selection->candidates.size(), 60u);
  for (const auto& c : model.selection->candidates) {
    EXPECT_EQ(c.inputs.contact.trim_fraction, 0.1);
    EXPECT_EQ(c.svm.degree, 1);
    EXPECT_EQ(c.inputs.contact.baseline_at, tactile::perception::ContactOptions::BaselineAt::none);
    EXPECT_EQ(c.tested, 16);
  }
  const auto& chosen = model.selection->candidates[model.selection->chosen];
  EXPECT_EQ(model.options.groups, chosen.inputs.groups);
  EXPECT_EQ(model.options.contact.electrodes, chosen.inputs.contact.electrodes);
  EXPECT_EQ(model.svm.c, chosen.svm.c);
}

TEST(ClassifyCli, BadInputNamesTheFile) {
  const tactile::test::TempDir dir_tmp("bad");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto model = (dir / "model.json").string();
  // The paper's inputs with a free-air baseline at the end, which the untared recordings below
  // need for "no contact" to mean anything (without a baseline, 1000 counts is contact).
  ASSERT_EQ(run_tactile("classify train --recordings " + kMaterials + " --labels " +
                        labels_of_trials(dir, "1") + " --out " + model +
                        " --baseline-at end --electrodes clusters --trim 0 --inputs "
                        "means,rates,hht")
                .exit_code,
            0);
  // A label the model does not know.
  std::ofstream(dir / "velvet.csv") << "file,class\nmat1_2_bio.csv,velvet\n";
  const auto unknown = run_tactile("classify test --model " + model + " --recordings " +
                                   kMaterials + " --labels " + (dir / "velvet.csv").string());
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find("mat1_2_bio.csv: unknown label 'velvet'"), std::string::npos)
      << unknown.output;
  // A recording with no contact, and one whose contact is too short for the windows.
  tactile::perception::SensorRecording flat;
  for (std::size_t i = 0; i < 100; ++i) {
    flat.t_s.push_back(static_cast<double>(i) / 100);
    flat.temperature_dc.push_back(2000);
    flat.temperature_ac.push_back(0);
    flat.pressure.push_back(1000);
    for (auto& e : flat.electrodes) e.push_back(3000);
    for (int k = 0; k < tactile::perception::kVibrationPerRow; ++k) flat.vibration.push_back(2000);
  }
  // A sensor whose every signal holds one value measured nothing: refused as such.
  tactile::perception::write_sensor_csv(dir / "constant_bio.csv", flat);
  // Free air has noise: one electrode's count flickers.
  for (std::size_t i = 0; i < 100; ++i) flat.electrodes[0][i] += static_cast<double>(i % 2);
  tactile::perception::write_sensor_csv(dir / "flat_bio.csv", flat);
  auto brief = flat;
  for (std::size_t i = 0; i < 5; ++i) brief.pressure[i] = 1100;
  tactile::perception::write_sensor_csv(dir / "brief_bio.csv", brief);
  const auto p =
      run_tactile("classify predict --model " + model + " " + (dir / "flat_bio.csv").string() +
                  " " + (dir / "brief_bio.csv").string() + " " +
                  (dir / "constant_bio.csv").string() + " " + kMaterials + "/mat14_2_bio.csv");
  EXPECT_EQ(p.exit_code, 1);
  EXPECT_NE(p.output.find("constant_bio.csv: pressure, vibration and all 19 electrodes hold one "
                          "value each over all 100 rows: the sensor measured nothing"),
            std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("flat_bio.csv: no contact"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("brief_bio.csv: feature contact of 5 rows is too short"),
            std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("mat14_2_bio.csv: mat"), std::string::npos) << p.output;  // the rest run
  std::ofstream(dir / "flat.csv") << "file,class\nflat_bio.csv,mat1\n";
  const auto t = run_tactile("classify train --recordings " + dir.string() + " --labels " +
                             (dir / "flat.csv").string() + " --out " + (dir / "x.json").string() +
                             " --baseline-at end");
  EXPECT_EQ(t.exit_code, 1);
  EXPECT_NE(t.output.find("flat_bio.csv: no contact"), std::string::npos) << t.output;
  // A model from another format version, and one whose inputs are not this program's.
  std::string text;
  {
    std::ifstream in(model);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto replaced = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    return text.substr(0, at) + to + text.substr(at + from.size());
  };
  ASSERT_NE(text.find("\"version\": 3"), std::string::npos);
  std::ofstream(dir / "v4.json") << replaced("\"version\": 3", "\"version\": 4");
  const auto v4 = run_tactile("classify predict --model " + (dir / "v4.json").string() + " " +
                              kMaterials + "/mat1_1_bio.csv");
  EXPECT_EQ(v4.exit_code, 1);
  EXPECT_NE(v4.output.find("v4.json: model format version 4"), std::string::npos) << v4.output;
  std::ofstream(dir / "inputs.json") << replaced("\"dp.vib.if_last\"", "\"dp.vib.if_end\"");
  const auto in =
      run_tactile("classify test --model " + (dir / "inputs.json").string() + " --recordings " +
                  kMaterials + " --labels " + kMaterials + "/labels.csv");
  EXPECT_EQ(in.exit_code, 1);
  EXPECT_NE(in.output.find("inputs.json: mismatched inputs"), std::string::npos) << in.output;
  // A labelled file missing from the folder.
  std::ofstream(dir / "gone.csv") << "file,class\nmat99_1_bio.csv,mat1\n";
  const auto gone = run_tactile("classify test --model " + model + " --recordings " + kMaterials +
                                " --labels " + (dir / "gone.csv").string());
  EXPECT_EQ(gone.exit_code, 1);
  EXPECT_NE(gone.output.find("mat99_1_bio.csv: labelled in"), std::string::npos) << gone.output;
}

TEST(ClassifyCli, UsageErrors) {
  EXPECT_EQ(run_tactile("classify").exit_code, 2);
  EXPECT_EQ(run_tactile("classify train --recordings " + kMaterials).exit_code, 2);
  const auto d = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             kMaterials + "/labels.csv --out /tmp/x.json --kernel-degree 3");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.output.find("--kernel-degree"), std::string::npos) << d.output;
  const auto g = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             kMaterials + "/labels.csv --out /tmp/x.json --inputs means,colour");
  EXPECT_EQ(g.exit_code, 2);
  EXPECT_NE(g.output.find("colour"), std::string::npos) << g.output;
  const auto p = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                             kMaterials + "/labels.csv --out /tmp/x.json --procedure tap");
  EXPECT_EQ(p.exit_code, 2);
  // The procedures' names from their table, in the words of every table's choice.
  EXPECT_NE(p.output.find("--procedure: unknown value 'tap' (known: stroke, static, dp, ru, roll)"),
            std::string::npos)
      << p.output;
  EXPECT_EQ(run_tactile("classify train --recordings " + kMaterials + " --labels " + kMaterials +
                        "/labels.csv --out /tmp/x.json --cv 1")
                .exit_code,
            2);
  // The options of real slides: a bad value is a usage error naming it.
  for (const auto& [option, named] :
       {std::pair<std::string, std::string>{"--trim 0.7", "trim fraction 0.7 is outside"},
        {"--trim -0.1", "trim fraction -0.1"},
        {"--electrodes all", "all"},
        {"--baseline-at middle", "middle"}}) {
    const auto r = run_tactile("classify train --recordings " + kMaterials + " --labels " +
                               kMaterials + "/labels.csv --out /tmp/x.json " + option);
    EXPECT_EQ(r.exit_code, 2) << option;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
  }
  EXPECT_EQ(
      run_tactile("classify predict --model /nonexistent.json " + kMaterials + "/mat1_1_bio.csv")
          .exit_code,
      2);
  // Without recordings the message names what is missing as `--help` shows it.
  const auto no_files = run_tactile("classify predict --model " + kMaterials + "/labels.csv");
  EXPECT_EQ(no_files.exit_code, 2);
  EXPECT_NE(no_files.output.find("RECORDINGS is required"), std::string::npos) << no_files.output;
}

// The simulated data set exported as recordings + labels (class: curvature, value: signed
// footprint) and classified with `tactile classify` gives `tactile perceive`'s Table 2: trained
// on trial 0 and tested on trial 1 (the split Table 2 uses with 2 trials per feature), each
// procedure's row has the same count correct and the same cascade RMS error.
TEST(ClassifyCli, SimulatedExportAgreesWithPerceiveTable2) {
  const tactile::test::TempDir dir_tmp("sim");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto p = run_tactile("perceive --out " + dir.string() +
                             " --trials 2 --footprints 1.25,20 --threads 2 --export-recordings "
                             "--export-trials 2");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  const auto table2 = read_csv_rows(dir / "table2.csv");
  const auto recordings = dir / "recordings";
  struct Row {
    std::string procedure;
    int degree;
  };
  for (const Row& row : {Row{"static", 1}, Row{"dp", 1}, Row{"dp", 2}, Row{"ru", 1}, Row{"roll", 1},
                         Row{"roll", 2}}) {
    const auto labels = read_csv_rows(recordings / ("labels_" + row.procedure + ".csv"));
    ASSERT_EQ(labels.size(), 1u + 12 * 2);
    for (const char* trial : {"0", "1"}) {
      std::ofstream out(dir / (std::string("trial") + trial + ".csv"));
      out << "file,class,value\n";
      for (std::size_t i = 1; i < labels.size(); ++i)
        if (labels[i][0].find(std::string("_t") + trial + "_") != std::string::npos)
          out << labels[i][0] << ',' << labels[i][1] << ',' << labels[i][2] << '\n';
    }
    const std::string what = row.procedure + " exp " + std::to_string(row.degree);
    const auto model = (dir / "model.json").string();
    const auto t = run_tactile("classify train --recordings " + recordings.string() + " --labels " +
                               (dir / "trial0.csv").string() + " --out " + model + " --procedure " +
                               row.procedure + " --baseline-at start" + " --kernel-degree " +
                               std::to_string(row.degree));
    ASSERT_EQ(t.exit_code, 0) << what << "\n" << t.output;
    const auto r = run_tactile("classify test --model " + model + " --recordings " +
                               recordings.string() + " --labels " + (dir / "trial1.csv").string());
    ASSERT_EQ(r.exit_code, 0) << what << "\n" << r.output;
    // table2.csv: inputs,degree,correct,tested,...,cascade_rms_mm (second to last).
    const auto match = std::find_if(table2.begin(), table2.end(), [&](const auto& fields) {
      return fields[0] == row.procedure && fields[1] == std::to_string(row.degree);
    });
    ASSERT_NE(match, table2.end()) << what;
    EXPECT_NE(r.output.find("(" + (*match)[2] + "/" + (*match)[3] + ")"), std::string::npos)
        << what << ": Table 2 has " << (*match)[2] << "/" << (*match)[3] << "\n"
        << r.output;
    const auto at = r.output.find("value: RMS error ");
    ASSERT_NE(at, std::string::npos) << r.output;
    const double rms = std::stod(r.output.substr(at + 17));
    const double table_rms = std::stod((*match)[match->size() - 2]);
    // The recordings are written with 3 decimals; the classifier prints 4 significant digits.
    EXPECT_NEAR(rms, table_rms, 1e-3 * table_rms + 1e-3) << what << "\n" << r.output;
  }
}
