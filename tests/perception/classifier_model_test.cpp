// Classifier of labelled recordings: labels file, inputs by group, model file round trip and
// its strict reading, bad recordings, and learning on the vendored real BioTac recordings.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/model_selection.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/report.hpp"

using tactile::test::error_of;

namespace perception = tactile::perception;

namespace {

const std::filesystem::path kMaterials =
    std::filesystem::path(TACTILE_TEST_DATA_DIR) / "biotac-materials";

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Labels of the vendored recordings whose trial number is in `trials` (e.g. "12": 1 and 2).
std::filesystem::path labels_of_trials(const std::filesystem::path& dir,
                                       const std::string& trials) {
  std::string text = "file,class\n";
  for (const char* m : {"mat1", "mat7", "mat14", "mat20"})
    for (char t : trials) text += std::string(m) + "_" + t + "_bio.csv," + m + "\n";
  const auto path = dir / ("labels_" + trials + ".csv");
  write_text(path, text);
  return path;
}

// A 1 s recording: pressure 1000 counts (free air) except `contact_rows` rows at 1100 at the
// start; electrodes and vibration constant.
perception::SensorRecording recording(std::size_t contact_rows) {
  perception::SensorRecording r;
  r.source = "made";
  for (std::size_t i = 0; i < 100; ++i) {
    r.t_s.push_back(static_cast<double>(i) / 100);
    r.temperature_dc.push_back(2000);
    r.temperature_ac.push_back(0);
    r.pressure.push_back(i < contact_rows ? 1100 : 1000);
    for (auto& e : r.electrodes) e.push_back(3000);
    for (int k = 0; k < perception::kVibrationPerRow; ++k) r.vibration.push_back(2000);
  }
  return r;
}

// The model file, as JSON, of the vendored trials 1 trained with `options`, written to dir/m.json.
nlohmann::json model_file_json(const std::filesystem::path& dir,
                               const perception::RecordingInputOptions& options = {}) {
  const auto data =
      perception::load_labelled_recordings(kMaterials, labels_of_trials(dir, "1"), options, {}, 2);
  perception::write_classifier_model(dir / "m.json", perception::make_classifier_model(data, {}));
  nlohmann::json j;
  std::ifstream(dir / "m.json") >> j;
  return j;
}

// The error of reading `j` as a model file (written to dir/bad.json), or "(no error)".
std::string model_file_error(const std::filesystem::path& dir, const nlohmann::json& j) {
  write_text(dir / "bad.json", j.dump());
  return error_of([&] { perception::read_classifier_model(dir / "bad.json"); });
}

}  // namespace

TEST(RecordingLabels, ReadsClassesAndValues) {
  const tactile::test::TempDir dir_tmp("labels");
  const std::filesystem::path& dir = dir_tmp.path();
  write_text(dir / "l.csv", "file,class,value\na_bio.csv,planar,-2.5\nb_bio.csv,conical,10\n");
  const auto l = perception::read_recording_labels(dir / "l.csv");
  ASSERT_EQ(l.rows.size(), 2u);
  EXPECT_TRUE(l.has_values);
  EXPECT_EQ(l.rows[0].file, "a_bio.csv");
  EXPECT_EQ(l.rows[1].label, "conical");
  EXPECT_DOUBLE_EQ(l.rows[0].value, -2.5);
}

TEST(RecordingLabels, TakesCrLfLineEndsAndAByteOrderMark) {
  const tactile::test::TempDir dir_tmp("labels_crlf");
  const std::filesystem::path& dir = dir_tmp.path();
  write_text(dir / "l.csv",
             "\xEF\xBB\xBF"
             "file,class,value\r\na_bio.csv,planar,-2.5\r\nb_bio.csv,conical,10\r\n");
  const auto l = perception::read_recording_labels(dir / "l.csv");
  ASSERT_EQ(l.rows.size(), 2u);
  EXPECT_TRUE(l.has_values);
  EXPECT_EQ(l.rows[0].file, "a_bio.csv");
  EXPECT_EQ(l.rows[1].label, "conical");
  EXPECT_DOUBLE_EQ(l.rows[1].value, 10);
}

TEST(RecordingLabels, MalformedFilesAreNamedErrors) {
  const tactile::test::TempDir dir_tmp("labels_bad");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto error = [&](const std::string& text) {
    write_text(dir / "bad.csv", text);
    return error_of([&] { perception::read_recording_labels(dir / "bad.csv"); });
  };
  EXPECT_NE(error("file,material\na.csv,x\n").find("needs columns 'file' and 'class'"),
            std::string::npos);
  EXPECT_NE(error("file,class\na.csv,x\na.csv,y\n").find("line 3: a.csv is labelled twice"),
            std::string::npos);
  EXPECT_NE(error("file,class\na.csv\n").find("line 2: 1 fields"), std::string::npos);
  EXPECT_NE(error("file,class,value\na.csv,x,big\n").find("value 'big' is not a number"),
            std::string::npos);
  EXPECT_NE(error("file,class\n").find("no labelled recordings"), std::string::npos);
  EXPECT_NE(error("file,class,weight\na.csv,x,1\n").find("unknown column 'weight'"),
            std::string::npos);
  EXPECT_NE(error("file,class,value\na.csv,x,nan\n").find("line 2: value is not finite (nan)"),
            std::string::npos);
  EXPECT_NE(error("file,class,value\na.csv,x,2e6\n")
                .find("line 2: value 2000000 is out of range: must be from -1000000 to 1000000"),
            std::string::npos);
  EXPECT_NE(error("file,class,file\na.csv,x,b.csv\n").find("column 'file' appears twice"),
            std::string::npos);
  // A labelled file is read from the recordings folder and names an output of `classify test`:
  // a path leading out of the folder is refused.
  for (const std::string file : {"../a.csv", "/etc/passwd", "sub/../../a.csv"})
    EXPECT_NE(error("file,class\n" + file + ",x\n")
                  .find("line 2: file '" + file + "' must be a path inside the recordings folder"),
              std::string::npos)
        << file;
  for (const auto& text : {"file,class\na.csv\n", "file,class\n"})
    EXPECT_NE(error(text).find((dir / "bad.csv").string()), std::string::npos) << text;
}

// The paper's groups are the 23 stroke inputs of procedure_inputs, in the same order.
TEST(RecordingInputs, PaperGroupsAreTheStrokeInputs) {
  perception::RecordingInputOptions o;
  EXPECT_EQ(perception::recording_input_names(o),
            perception::procedure_input_names(perception::Procedure::distal_proximal));
  const auto r = perception::read_sensor_csv(kMaterials / "mat1_1_bio.csv");
  EXPECT_EQ(perception::recording_inputs(r, o),
            perception::procedure_inputs(r, perception::Procedure::distal_proximal, o.contact));
  o.groups = {
      perception::InputGroup::bands,
      perception::InputGroup::hht};  // order of the groups is fixed whatever the order asked
  const auto names = perception::recording_input_names(o);
  ASSERT_EQ(names.size(), 2u + 7u);
  EXPECT_EQ(names[0], "dp.vib.if_first");
  EXPECT_EQ(names[2], "dp.band.10_20hz");
  EXPECT_EQ(perception::recording_inputs(r, o).size(), names.size());
  o.procedure = perception::Procedure::static_contact;
  EXPECT_NE(error_of([&] {
              perception::recording_input_names(o);
            }).find("input group 'bands' does not apply to static"),
            std::string::npos);
}

TEST(ClassifierModel, FileRoundTripGivesTheSameModelAndPredictions) {
  const tactile::test::TempDir dir_tmp("round_trip");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto data =
      perception::load_labelled_recordings(kMaterials, kMaterials / "labels.csv", {}, {}, 2);
  ASSERT_EQ(data.rows.size(), 16u);
  ASSERT_EQ(data.class_names.size(), 4u);
  perception::SvmOptions svm;
  svm.degree = 2;
  svm.c = 3;
  const auto model = perception::make_classifier_model(data, svm);
  perception::write_classifier_model(dir / "m.json", model);
  const auto back = perception::read_classifier_model(dir / "m.json");
  EXPECT_EQ(back.version, perception::kClassifierModelVersion);
  EXPECT_EQ(back.options.groups, model.options.groups);
  EXPECT_EQ(back.input_names, model.input_names);
  EXPECT_EQ(back.class_names, model.class_names);
  EXPECT_EQ(back.files, model.files);
  EXPECT_EQ(back.rows, model.rows);  // doubles survive JSON exactly (shortest round trip)
  EXPECT_EQ(back.classes, model.classes);
  EXPECT_EQ(back.scaler.min, model.scaler.min);
  EXPECT_EQ(back.svm.degree, 2);
  EXPECT_EQ(back.svm.c, 3.0);
  const perception::Classifier a(model), b(back);
  for (const auto& row : data.rows)
    EXPECT_EQ(a.predict(row).class_index, b.predict(row).class_index);
}

TEST(ClassifierModel, OtherVersionAndMismatchedInputsAreNamedErrors) {
  const tactile::test::TempDir dir_tmp("model_bad");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto good = model_file_json(dir);
  const auto error = [&](const nlohmann::json& j) { return model_file_error(dir, j); };
  auto j = good;
  j["version"] = perception::kClassifierModelVersion + 1;
  EXPECT_NE(error(j).find("model format version 4, this program reads versions 1 to 3"),
            std::string::npos)
      << error(j);
  // A version beyond int, whose low 32 bits are 1, and versions below 1, are not version 1.
  for (const nlohmann::json& v : {nlohmann::json(4294967297ULL), nlohmann::json(0),
                                  nlohmann::json(-4294967295LL), nlohmann::json(~0ULL)}) {
    j = good;
    j["version"] = v;
    EXPECT_NE(error(j).find("model format version " + v.dump() + ", this program reads"),
              std::string::npos)
        << error(j);
  }
  j = good;
  j["input_names"][0] = "dp.w1.temperature";
  EXPECT_NE(error(j).find("mismatched inputs"), std::string::npos);
  j = good;
  j["input_groups"] = {"means"};  // names of 23 inputs, groups of 14
  EXPECT_NE(error(j).find("mismatched inputs"), std::string::npos);
  j = good;
  j["input_groups"] = {"means", "colour"};
  EXPECT_NE(
      error(j).find("unknown input group 'colour' (known: means, rates, hht, bands, stds, stats)"),
      std::string::npos)
      << error(j);
  j = good;
  j["training"][0]["inputs"].erase(0);
  EXPECT_NE(error(j).find("has 22 inputs, the model 23"), std::string::npos);
  j = good;
  j.erase("svm");
  EXPECT_NE(error(j).find("missing field 'svm'"), std::string::npos);
  write_text(dir / "bad.json", "{\"version\": 1,");
  EXPECT_NE(
      error_of([&] { perception::read_classifier_model(dir / "bad.json"); }).find("not valid JSON"),
      std::string::npos);
  EXPECT_NE(error(j).find((dir / "bad.json").string()), std::string::npos);
}

// Found by the second hostile-input run: the classifier is retrained from the stored rows, so
// a row or scaler edited by hand changed every prediction and the file was still read.
TEST(ClassifierModel, TamperedTrainingRowsAndScalerAreNamedErrors) {
  const tactile::test::TempDir dir_tmp("model_tampered");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto good = model_file_json(dir);
  const auto error = [&](const nlohmann::json& j) { return model_file_error(dir, j); };
  EXPECT_EQ(error(good), "(no error)");
  auto j = good;
  j["training"][1]["inputs"][0] = 1e300;
  EXPECT_NE(error(j).find("= 1e+300 is not a finite number"), std::string::npos) << error(j);
  j = good;
  j["scaler"]["max"][2] = j["scaler"]["max"][2].get<double>() * 0.5 - 1;
  EXPECT_NE(error(j).find("but its training rows span"), std::string::npos) << error(j);
  j = good;
  j["scaler"]["min"][0] = j["scaler"]["min"][0].get<double>() - 1;
  EXPECT_NE(error(j).find("scaler of input "), std::string::npos) << error(j);
  j = good;
  j["class_names"].push_back("glass");  // a class no row teaches
  EXPECT_NE(error(j).find("class 'glass' has no training row"), std::string::npos) << error(j);
}

TEST(LabelledRecordings, BadRecordingsAndLabelsNameTheFile) {
  const tactile::test::TempDir dir_tmp("recordings_bad");
  const std::filesystem::path& dir = dir_tmp.path();
  // Free air: no contact, one electrode's noise of a count (a sensor whose every signal holds
  // one value measured nothing at all, refused when read).
  auto flat = recording(0);
  for (std::size_t i = 0; i < flat.rows(); ++i) flat.electrodes[0][i] += static_cast<double>(i % 2);
  perception::write_sensor_csv(dir / "flat_bio.csv", flat);
  perception::write_sensor_csv(dir / "constant_bio.csv", recording(0));
  perception::write_sensor_csv(dir / "brief_bio.csv", recording(5));
  perception::write_sensor_csv(dir / "good_bio.csv", recording(60));
  const auto error = [&](const std::string& labels,
                         const std::vector<std::string>& known_classes = {}) {
    write_text(dir / "labels.csv", "file,class\n" + labels);
    return error_of([&] {
      perception::load_labelled_recordings(dir, dir / "labels.csv", {}, known_classes, 1);
    });
  };
  const auto no_contact = error("flat_bio.csv,x\n");
  EXPECT_NE(no_contact.find("flat_bio.csv"), std::string::npos) << no_contact;
  EXPECT_NE(no_contact.find("no contact"), std::string::npos) << no_contact;
  const auto constant = error("constant_bio.csv,x\n");
  EXPECT_NE(constant.find("constant_bio.csv: pressure, vibration and all 19 electrodes hold one "
                          "value each over all 100 rows: the sensor measured nothing"),
            std::string::npos)
      << constant;
  const auto brief = error("brief_bio.csv,x\n");
  EXPECT_NE(brief.find("brief_bio.csv"), std::string::npos) << brief;
  EXPECT_NE(brief.find("too short for two windows"), std::string::npos) << brief;
  const auto missing = error("gone_bio.csv,x\n");
  EXPECT_NE(missing.find("gone_bio.csv: labelled in"), std::string::npos) << missing;
  // Which folder it was looked for in: the labels may belong to another one.
  EXPECT_NE(missing.find("but not in the recordings folder"), std::string::npos) << missing;
  const auto unknown = error("good_bio.csv,velvet\n", {"mat1", "mat7"});
  EXPECT_NE(unknown.find("good_bio.csv: unknown label 'velvet'"), std::string::npos) << unknown;
  EXPECT_EQ(error("good_bio.csv,x\n"), "(no error)");
}

// Trained on trials 1 and 2 of the 4 vendored materials, tested on trials 3 and 4: 8 held-out
// recordings, chance 1 in 4. At least 6 of 8 right by chance has probability 0.004 (binomial),
// so a classifier that reaches it learns the material from the signals.
TEST(Classifier, LearnsRealMaterialsBetterThanChance) {
  const tactile::test::TempDir dir_tmp("learn");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto train =
      perception::load_labelled_recordings(kMaterials, labels_of_trials(dir, "12"), {}, {}, 2);
  const auto model = perception::make_classifier_model(train, {});
  const auto test = perception::load_labelled_recordings(kMaterials, labels_of_trials(dir, "34"),
                                                         model.options, model.class_names, 2);
  const auto t = perception::test_classifier(perception::Classifier(model), 4, test);
  EXPECT_EQ(t.tested, 8);
  EXPECT_GE(t.correct, 6);
  int counted = 0;
  for (const auto& row : t.confusion)
    for (int v : row) counted += v;
  EXPECT_EQ(counted, 8);
}

// The inputs of real slides (clusters, no baseline, trimmed, means and bands) learn the
// vendored materials too: at least 7 of the 8 held-out recordings, which chance (1 in 4) gives
// with probability 0.0004 (binomial).
TEST(Classifier, SlideDefaultsLearnRealMaterials) {
  const tactile::test::TempDir dir_tmp("learn_slide");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto options = perception::default_recording_inputs(perception::RecordingProcedure::stroke);
  const auto train =
      perception::load_labelled_recordings(kMaterials, labels_of_trials(dir, "12"), options, {}, 2);
  const auto model = perception::make_classifier_model(
      train, perception::default_svm_options(perception::RecordingProcedure::stroke));
  const auto test = perception::load_labelled_recordings(kMaterials, labels_of_trials(dir, "34"),
                                                         options, model.class_names, 2);
  const auto t = perception::test_classifier(perception::Classifier(model), 4, test);
  EXPECT_EQ(t.tested, 8);
  EXPECT_GE(t.correct, 7);
}

// Stratified folds: with 4 trials of each of 4 classes and 4 folds, every fold tests one trial
// of every class; the pooled count is the sum over folds.
TEST(Classifier, CrossValidationIsStratifiedAndPooled) {
  const auto data =
      perception::load_labelled_recordings(kMaterials, kMaterials / "labels.csv", {}, {}, 2);
  const auto cv = perception::cross_validate(data, {}, 4, 2);
  ASSERT_EQ(cv.fold_accuracy.size(), 4u);
  EXPECT_EQ(cv.tested, 16);
  double sum = 0;
  for (double a : cv.fold_accuracy) {
    sum += a;
    const double quarters = a * 4;  // 4 test rows per fold
    EXPECT_DOUBLE_EQ(quarters, std::round(quarters));
  }
  EXPECT_DOUBLE_EQ(sum / 4, cv.mean);
  EXPECT_EQ(cv.correct, static_cast<int>(std::lround(sum * 4)));
  EXPECT_THROW(perception::cross_validate(data, {}, 1, 1), std::invalid_argument);
}

// A procedure's name reads back as itself: stroke and static are real recordings' (all contact
// is feature contact), dp, ru and roll the paper's scenes (feature contact from kinematics), named
// as their inputs are; any other name is refused with the list of the known ones.
TEST(RecordingInputs, ProcedureNamesRoundTrip) {
  for (const char* name : {"stroke", "static", "dp", "ru", "roll"}) {
    perception::RecordingInputOptions o;
    perception::set_recording_procedure(o, perception::parse_recording_procedure(name));
    EXPECT_EQ(to_string(perception::recording_procedure(o)), name);
  }
  perception::RecordingInputOptions o;
  perception::set_recording_procedure(o, perception::RecordingProcedure::radial_ulnar);
  EXPECT_TRUE(o.contact.feature_from_kinematics);
  EXPECT_EQ(perception::recording_input_names(o).front(), "ru.w1.pressure");
  EXPECT_EQ(to_string(perception::RecordingProcedure::radial_ulnar),
            perception::procedure_short_name(perception::Procedure::radial_ulnar));
  perception::set_recording_procedure(o, perception::RecordingProcedure::stroke);
  EXPECT_FALSE(o.contact.feature_from_kinematics);
  try {
    perception::parse_recording_procedure("tap");
    ADD_FAILURE() << "'tap' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown procedure 'tap' (known: stroke, static, dp, ru, roll)");
  }
}

// Input groups are named in model files and on the command line: names round-trip, keep their
// spelling, and an unknown one is refused with the accepted ones.
TEST(RecordingInputs, InputGroupNamesRoundTrip) {
  for (const auto g : perception::kInputGroups)
    EXPECT_EQ(perception::parse_input_group(perception::to_string(g)), g);
  EXPECT_EQ(perception::to_string(perception::InputGroup::hht), "hht");
  EXPECT_EQ(perception::to_string(perception::InputGroup::bands), "bands");
  const std::string message = error_of([] { perception::parse_input_group("spectrum"); });
  EXPECT_NE(message.find("'spectrum'"), std::string::npos) << message;
  EXPECT_NE(message.find("means, rates, hht, bands, stds, stats"), std::string::npos) << message;
}

// stds: the population standard deviation of each signal over the feature contact. Pressure
// alternates 1090 / 1110 over the 60 contact rows (deviation 10), electrode 3 climbs by 1 a row
// (0..59: deviation sqrt((60^2 - 1) / 12)), the other electrodes are constant (0).
TEST(RecordingInputs, StdsAreTheSpreadOfEachSignalOverTheContact) {
  auto r = recording(60);
  for (std::size_t i = 0; i < 60; ++i) {
    r.pressure[i] = i % 2 ? 1110 : 1090;
    r.electrodes[2][i] = 3000 + static_cast<double>(i);
  }
  perception::RecordingInputOptions o;
  o.groups = {perception::InputGroup::stds};
  o.contact.electrodes = perception::ContactOptions::Electrodes::each;
  const auto names = perception::recording_input_names(o);
  const auto in = perception::recording_inputs(r, o);
  ASSERT_EQ(names.size(), 20u);
  ASSERT_EQ(in.size(), 20u);
  EXPECT_EQ(names[0], "dp.std.pressure");
  EXPECT_EQ(names[3], "dp.std.e3");
  EXPECT_DOUBLE_EQ(in[0], 10);
  EXPECT_NEAR(in[3], std::sqrt((60.0 * 60.0 - 1) / 12), 1e-9);
  for (std::size_t k : {1u, 2u, 4u, 19u}) EXPECT_DOUBLE_EQ(in[k], 0) << names[k];
}

// The paper's scenes keep the paper's inputs by default; real slides get theirs.
TEST(RecordingInputs, DefaultsByProcedure) {
  using perception::ContactOptions;
  for (const auto procedure :
       {perception::RecordingProcedure::distal_proximal,
        perception::RecordingProcedure::radial_ulnar, perception::RecordingProcedure::roll}) {
    const auto scene = to_string(procedure);
    const auto o = perception::default_recording_inputs(procedure);
    EXPECT_EQ(tactile::names_of(o.groups), (std::vector<std::string>{"means", "rates", "hht"}))
        << scene;
    EXPECT_EQ(o.contact.electrodes, ContactOptions::Electrodes::clusters) << scene;
    EXPECT_EQ(o.contact.trim_fraction, 0.0) << scene;
    EXPECT_EQ(perception::recording_input_names(o).size(), 23u) << scene;
  }
  EXPECT_EQ(perception::recording_input_names(perception::default_recording_inputs(
                perception::RecordingProcedure::static_contact)),
            perception::procedure_input_names(perception::Procedure::static_contact));
  const auto slide = perception::default_recording_inputs(perception::RecordingProcedure::stroke);
  EXPECT_EQ(tactile::names_of(slide.groups), (std::vector<std::string>{"means", "bands"}));
  EXPECT_EQ(slide.contact.baseline_at, ContactOptions::BaselineAt::none);
  EXPECT_EQ(slide.contact.electrodes, ContactOptions::Electrodes::clusters);
  EXPECT_EQ(slide.contact.trim_fraction, 0.2);
  EXPECT_EQ(perception::recording_input_names(slide).size(), 14u + 7u);
  EXPECT_EQ(perception::default_svm_options(perception::RecordingProcedure::stroke).c, 100.0);
  EXPECT_EQ(perception::default_svm_options(perception::RecordingProcedure::distal_proximal).c,
            1.0);
  EXPECT_EQ(perception::default_svm_options(perception::RecordingProcedure::stroke).degree, 1);
}

// A training's options: unset ones are the procedure's defaults, set ones replace them, and a
// trim outside [0, 0.5) is refused before any recording is read.
TEST(ClassifierTraining, SetOptionsReplaceTheProceduresDefaults) {
  using perception::ContactOptions;
  perception::ClassifierTraining defaults;
  defaults.procedure = perception::RecordingProcedure::distal_proximal;
  const auto in = perception::recording_inputs_for(defaults);
  EXPECT_EQ(tactile::names_of(in.groups), (std::vector<std::string>{"means", "rates", "hht"}));
  EXPECT_EQ(in.contact.baseline_at, ContactOptions::BaselineAt::end);
  EXPECT_EQ(perception::svm_options_for(defaults).c, 1.0);
  perception::ClassifierTraining set;
  set.baseline_at = ContactOptions::BaselineAt::start;
  set.electrodes = ContactOptions::Electrodes::each;
  set.trim = 0.25;
  set.inputs = {perception::InputGroup::stds};
  set.kernel_degree = 2;
  set.c = 3.5;
  const auto custom = perception::recording_inputs_for(set);
  EXPECT_EQ(tactile::names_of(custom.groups), (std::vector<std::string>{"stds"}));
  EXPECT_EQ(custom.contact.baseline_at, ContactOptions::BaselineAt::start);
  EXPECT_EQ(custom.contact.electrodes, ContactOptions::Electrodes::each);
  EXPECT_EQ(custom.contact.trim_fraction, 0.25);
  EXPECT_EQ(perception::svm_options_for(set).degree, 2);
  EXPECT_EQ(perception::svm_options_for(set).c, 3.5);
  set.trim = 0.5;
  EXPECT_THROW(perception::recording_inputs_for(set), std::invalid_argument);
}

// Model files of version 1 (before trim and electrodes) read as clusters without trim; the new
// fields, when present, are checked.
TEST(ClassifierModel, ReadsVersionOneAndChecksTheNewFields) {
  const tactile::test::TempDir dir_tmp("model_v1");
  const std::filesystem::path& dir = dir_tmp.path();
  const auto options = perception::default_recording_inputs(perception::RecordingProcedure::stroke);
  const auto good = model_file_json(dir, options);
  const auto back = perception::read_classifier_model(dir / "m.json");
  EXPECT_EQ(back.options.contact.electrodes, options.contact.electrodes);
  EXPECT_EQ(back.options.contact.trim_fraction, options.contact.trim_fraction);
  EXPECT_EQ(back.options.contact.baseline_at, options.contact.baseline_at);
  EXPECT_EQ(back.input_names, perception::recording_input_names(options));
  const auto error = [&](const nlohmann::json& j) { return model_file_error(dir, j); };
  auto j = good;
  j["contact"]["electrodes"] = "all";
  EXPECT_NE(error(j).find("'all'"), std::string::npos) << error(j);
  j = good;
  j["contact"]["trim_fraction"] = 0.7;
  EXPECT_NE(error(j).find("trim fraction 0.7"), std::string::npos) << error(j);
  j = good;
  j["contact"].erase("trim_fraction");
  EXPECT_NE(error(j).find("missing field 'trim_fraction'"), std::string::npos) << error(j);
  // A version 1 file of the paper's inputs (clusters, no trim, no new fields) still reads.
  j = model_file_json(dir);
  j["version"] = 1;
  j["contact"].erase("trim_fraction");
  j["contact"].erase("electrodes");
  EXPECT_EQ(error(j), "(no error)");
  const auto v1 = perception::read_classifier_model(dir / "bad.json");
  EXPECT_EQ(v1.options.contact.electrodes, perception::ContactOptions::Electrodes::clusters);
  EXPECT_EQ(v1.options.contact.trim_fraction, 0.0);
  EXPECT_EQ(v1.input_names, perception::recording_input_names({}));
}

// stats: mean and standard deviation of pressure and of each cluster over the contact (baseline
// at the end: free air at 1000 counts), the vibration's standard deviation, then the same 7 band
// powers as the bands group. Pressure alternates 1090 / 1110 over the 60 contact rows (mean
// 100 above the baseline, deviation 10); the vibration alternates 1995 / 2005 over the contact
// (deviation 5); the electrodes are constant (0, 0).
TEST(RecordingInputs, StatsAreMeansStdsVibrationAndBands) {
  auto r = recording(60);
  for (std::size_t i = 0; i < 60; ++i) r.pressure[i] = i % 2 ? 1110 : 1090;
  for (std::size_t i = 0; i < 60 * perception::kVibrationPerRow; ++i)
    r.vibration[i] = i % 2 ? 2005 : 1995;
  perception::RecordingInputOptions o;
  o.groups = {perception::InputGroup::stats};
  const auto names = perception::recording_input_names(o);
  const auto in = perception::recording_inputs(r, o);
  ASSERT_EQ(names.size(), 7u * 2 + 1 + 7);
  ASSERT_EQ(in.size(), names.size());
  EXPECT_EQ(names[0], "dp.mean.pressure");
  EXPECT_EQ(names[1], "dp.std.pressure");
  EXPECT_EQ(names[14], "dp.std.vibration");
  EXPECT_EQ(names[15], "dp.band.10_20hz");
  EXPECT_DOUBLE_EQ(in[0], 100);
  EXPECT_DOUBLE_EQ(in[1], 10);
  for (std::size_t k = 2; k < 14; ++k) EXPECT_DOUBLE_EQ(in[k], 0) << names[k];
  EXPECT_DOUBLE_EQ(in[14], 5);
  o.groups = {perception::InputGroup::bands};
  const auto bands = perception::recording_inputs(r, o);
  EXPECT_EQ(std::vector<double>(in.begin() + 15, in.end()), bands);
  // 19 electrodes: 2 x 20 + 1 + 7, the 48 plain statistics.
  o.groups = {perception::InputGroup::stats};
  o.contact.electrodes = perception::ContactOptions::Electrodes::each;
  EXPECT_EQ(perception::recording_input_names(o).size(), 48u);
  // stats hold bands and stds: asking for both is refused, naming the group.
  for (const auto g : {perception::InputGroup::bands, perception::InputGroup::stds}) {
    o.groups = {perception::InputGroup::stats, g};
    EXPECT_NE(error_of([&] {
                perception::recording_input_names(o);
              }).find("input group '" + perception::to_string(g) + "' is part of 'stats'"),
              std::string::npos);
  }
  o.procedure = perception::Procedure::static_contact;
  o.groups = {perception::InputGroup::stats};
  EXPECT_EQ(perception::recording_input_names(o).size(), 48u);
}

// Selection on the vendored recordings between the plain statistics and the HHT alone (two
// numbers that carry next to nothing about a texture: 0.09 over 20 materials, chance 0.05):
// every fold's inner loop and the selection on all rows choose the statistics, the nested
// figure tests every recording once, and a model of the choice records it and reads back.
TEST(ModelSelection, ChoosesByInnerFoldsAndScoresByOuterFolds) {
  const tactile::test::TempDir dir_tmp("select");
  const auto data =
      perception::read_labelled_recordings(kMaterials, kMaterials / "labels.csv", {}, 2);
  auto grid = perception::default_selection_grid(perception::RecordingProcedure::stroke);
  grid.input_sets = {{perception::InputGroup::hht}, {perception::InputGroup::stats}};
  grid.baselines = {perception::ContactOptions::BaselineAt::none};
  grid.electrodes = {perception::ContactOptions::Electrodes::clusters};
  grid.trims = {0.1};
  grid.degrees = {1};
  grid.cs = {1, 10};
  ASSERT_EQ(grid.size(), 4u);
  const auto base = perception::default_recording_inputs(perception::RecordingProcedure::stroke);
  const auto nested = perception::nested_cross_validate(data, base, grid, 4, 5, 2);
  EXPECT_EQ(nested.outer.tested, 16);
  ASSERT_EQ(nested.chosen.size(), 4u);
  for (const auto& c : nested.chosen) {
    EXPECT_EQ(tactile::names_of(c.inputs.groups), std::vector<std::string>{"stats"});
    EXPECT_EQ(c.tested, 12);  // the inner loop saw the 12 training rows of its fold only
  }
  EXPECT_EQ(nested.overall.folds, 4);  // 5 asked, lowered to the 4 trials of each class
  ASSERT_EQ(nested.overall.candidates.size(), 4u);
  const auto& chosen = nested.overall.candidates[nested.overall.chosen];
  EXPECT_EQ(tactile::names_of(chosen.inputs.groups), std::vector<std::string>{"stats"});
  for (const auto& c : nested.overall.candidates) EXPECT_LE(c.correct, chosen.correct);
  // The same choice alone; the model carries it, in version 3 files, and reads back.
  const auto record = perception::select_options(data, base, grid, 5, {}, 2);
  EXPECT_EQ(record.chosen, nested.overall.chosen);
  const auto model = perception::make_selected_model(data, record, 2);
  EXPECT_EQ(model.svm.c, chosen.svm.c);
  EXPECT_EQ(model.input_names, perception::recording_input_names(chosen.inputs));
  const auto path = dir_tmp.path() / "m.json";
  perception::write_classifier_model(path, model);
  const auto back = perception::read_classifier_model(path);
  ASSERT_TRUE(back.selection.has_value());
  EXPECT_EQ(back.selection->chosen, record.chosen);
  EXPECT_EQ(back.selection->folds, 4);
  ASSERT_EQ(back.selection->candidates.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(back.selection->candidates[k].correct, record.candidates[k].correct);
    EXPECT_EQ(back.selection->candidates[k].svm.c, record.candidates[k].svm.c);
    EXPECT_EQ(back.selection->candidates[k].inputs.groups, record.candidates[k].inputs.groups);
  }
  // A class with one recording leaves nothing to cross-validate the choice with.
  EXPECT_NE(error_of([&] {
              perception::select_options(data, base, grid, 5, {0, 1, 4}, 1);
            }).find("at least 2 recordings of every class"),
            std::string::npos);
}

// The selection scores each candidate by sharing one kernel matrix among the exponents and
// values of C of each fold: every count must be the candidate's own cross-validation, on all
// rows and on a subset (trials 1-3, folds lowered to 3).
TEST(ModelSelection, ScoresAreEachCandidatesCrossValidation) {
  const auto data =
      perception::read_labelled_recordings(kMaterials, kMaterials / "labels.csv", {}, 2);
  auto grid = perception::default_selection_grid(perception::RecordingProcedure::stroke);
  grid.input_sets = {{perception::InputGroup::stats},
                     {perception::InputGroup::means, perception::InputGroup::bands}};
  grid.baselines = {perception::ContactOptions::BaselineAt::none};
  grid.electrodes = {perception::ContactOptions::Electrodes::clusters};
  grid.trims = {0.1};
  grid.degrees = {1, 2};
  grid.cs = {0.01, 1, 1000};
  const auto base = perception::default_recording_inputs(perception::RecordingProcedure::stroke);
  std::vector<std::size_t> first_three;
  for (std::size_t i = 0; i < data.files.size(); ++i)
    if (data.files[i].find("_4_") == std::string::npos) first_three.push_back(i);
  ASSERT_EQ(first_three.size(), 12u);
  for (const auto& rows : {std::vector<std::size_t>{}, first_three}) {
    const auto record = perception::select_options(data, base, grid, 5, rows, 2);
    ASSERT_EQ(record.candidates.size(), 12u);
    EXPECT_EQ(record.folds, rows.empty() ? 4 : 3);
    int lowest = 1000, highest = -1;
    for (const auto& c : record.candidates) {
      auto inputs = perception::analyse_recordings(data, c.inputs, 2);
      if (!rows.empty()) inputs = perception::subset(inputs, rows);
      const auto cv = perception::cross_validate(inputs, c.svm, record.folds, 1);
      EXPECT_EQ(c.correct, cv.correct) << perception::describe_candidate(c);
      EXPECT_EQ(c.tested, cv.tested);
      lowest = std::min(lowest, c.correct);
      highest = std::max(highest, c.correct);
    }
    EXPECT_LT(lowest, highest);  // the candidates differ, so equal counts are no accident
  }
}

// The default grid reaches past the slide default's C on both sides: a default chosen at the
// grid's end would not say whether a larger or smaller C is better still.
TEST(ModelSelection, SlideDefaultCIsInsideTheGrid) {
  const auto grid = perception::default_selection_grid(perception::RecordingProcedure::stroke);
  const auto [lo, hi] = std::minmax_element(grid.cs.begin(), grid.cs.end());
  const double c = perception::default_svm_options(perception::RecordingProcedure::stroke).c;
  EXPECT_LT(*lo, c);
  EXPECT_GT(*hi, c);
  EXPECT_NE(std::find(grid.cs.begin(), grid.cs.end(), c), grid.cs.end());
}

// `classify train --select` searches only what the user left unset: the stroke grid (5 input
// sets, 2 baselines, 2 electrode signals, 3 trims, 2 exponents, 6 values of C) with trim,
// exponent and baseline named is 5 x 2 x 6 candidates; a bad trim is refused as without
// --select, and so is one class, before anything is selected.
TEST(ModelSelection, NamedOptionsAreNotSearched) {
  perception::ClassifierTraining t;
  EXPECT_EQ(perception::selection_grid_for(t).size(), 5u * 2 * 2 * 3 * 2 * 6);
  t.trim = 0.1;
  t.kernel_degree = 1;
  t.baseline_at = perception::ContactOptions::BaselineAt::none;
  const auto grid = perception::selection_grid_for(t);
  EXPECT_EQ(grid.size(), 60u);
  EXPECT_EQ(grid.trims, std::vector<double>{0.1});
  EXPECT_EQ(grid.degrees, std::vector<int>{1});
  t.trim = 0.5;
  EXPECT_THROW(perception::selection_grid_for(t), std::invalid_argument);
  t.trim = 0.1;
  t.select = true;
  const tactile::test::TempDir dir_tmp("one_class");
  const auto labels = dir_tmp.path() / "one.csv";
  write_text(labels, "file,class\nmat1_1_bio.csv,mat1\nmat1_2_bio.csv,mat1\n");
  EXPECT_NE(error_of([&] {
              perception::train_classifier(kMaterials, labels, t, 1);
            }).find("at least 2 classes"),
            std::string::npos);
}

// Version 2 files (no selection) still read; a version 3 file's selection is checked.
TEST(ClassifierModel, ReadsVersionTwoAndChecksTheSelection) {
  const tactile::test::TempDir dir_tmp("model_v2");
  const std::filesystem::path& dir = dir_tmp.path();
  auto j = model_file_json(dir);
  const auto error = [&](const nlohmann::json& k) { return model_file_error(dir, k); };
  j["version"] = 2;
  EXPECT_EQ(error(j), "(no error)");
  EXPECT_FALSE(perception::read_classifier_model(dir / "bad.json").selection.has_value());
  j["version"] = 3;
  j["selection"] = {{"folds", 5},
                    {"chosen", 1},
                    {"candidates",
                     {{{"input_groups", {"stats"}},
                       {"baseline_at", "none"},
                       {"electrodes", "each"},
                       {"trim_fraction", 0.1},
                       {"degree", 1},
                       {"c", 1.0},
                       {"correct", 3},
                       {"tested", 4}}}}};
  EXPECT_NE(error(j).find("selection: chosen 1 is not one of the 1 candidates"), std::string::npos)
      << error(j);
  j["selection"]["chosen"] = 0;
  EXPECT_EQ(error(j), "(no error)");
  j["selection"]["candidates"][0]["electrodes"] = "some";
  EXPECT_NE(error(j).find("'some'"), std::string::npos) << error(j);
}

// Classes confused with each other sit next to each other: 0 and 3 are confused 3 times, 1 and 2
// once, 4 never; the chain starts at the most confused pair.
TEST(ConfusionOrder, PutsConfusedClassesTogether) {
  const std::vector<std::vector<int>> confusion = {
      {5, 0, 0, 2, 0}, {0, 6, 1, 0, 0}, {0, 0, 7, 0, 0}, {1, 0, 0, 4, 0}, {0, 0, 0, 0, 5}};
  EXPECT_EQ(perception::confusion_order(confusion), (std::vector<std::size_t>{0, 3, 1, 2, 4}));
  // A chain grows at either end: 2 is confused with 0 and 0 with 1, so 2, 0, 1 (or reversed).
  const std::vector<std::vector<int>> chain = {{5, 3, 1}, {0, 5, 0}, {1, 0, 5}};
  EXPECT_EQ(perception::confusion_order(chain), (std::vector<std::size_t>{2, 0, 1}));
  const std::vector<std::vector<int>> none = {{3, 0}, {0, 3}};
  EXPECT_EQ(perception::confusion_order(none), (std::vector<std::size_t>{0, 1}));
}
