#pragma once
// A classifier of labelled real recordings (a material, a feature): the recordings' inputs
// (recording_inputs.hpp), WEKA-style [0, 1] scaling and an SVC (svm_model.hpp), and, when the
// labels carry a numeric value, one SVR per class for the value, used after the SVC as the
// paper's cascade uses its curvature-specific SVRs.
//
// The model file is strict JSON (docs/formats.md): format version, input procedure and groups,
// input names, class names, SVM settings, the scaling, and the training set itself (file, class,
// value, inputs). The SVM is refitted from that training set when the file is read: libsvm's
// training is deterministic, so the refitted machine is the one that was trained, and the file
// does not depend on libsvm's internal model layout.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tactile/perception/recording_inputs.hpp"
#include "tactile/perception/svm_model.hpp"

namespace tactile::perception {

// Version 2 added contact.trim_fraction and contact.electrodes, version 3 the optional
// `selection` (what `classify train --select` compared); versions 1 and 2 are still read.
inline constexpr int kClassifierModelVersion = 3;

// One row of a labels file `file,class[,value]`.
struct RecordingLabel {
  std::string file;
  std::string label;
  double value = 0;  // only when the file has a value column
};
struct RecordingLabels {
  std::vector<RecordingLabel> rows;
  bool has_values = false;
};

// Throws tactile::FormatError naming the file and line: no header or a header without `file`
// and `class` (or with columns other than `value`), a missing field, a file listed twice, a
// non-numeric value, no rows.
RecordingLabels read_recording_labels(const std::filesystem::path& path);

// Inputs of labelled recordings. `class_names` are in order of first appearance in the labels.
struct LabelledInputs {
  RecordingInputOptions options;
  std::vector<std::string> input_names;
  std::vector<std::string> class_names;
  std::vector<std::string> files;
  SvmRows rows;
  std::vector<int> classes;    // index in class_names
  std::vector<double> values;  // per row; empty without a value column
};

// Labelled recordings as read, before analysis (model selection analyses them many ways).
struct LabelledRecordings {
  std::vector<std::string> class_names;  // in order of first appearance in the labels
  std::vector<std::string> files;
  std::vector<SensorRecording> recordings;
  std::vector<int> classes;    // index in class_names
  std::vector<double> values;  // per row; empty without a value column
};

// Reads every recording the labels name, in `dir`, on `threads` workers (0: all cores). With
// `known_classes` (testing a model), a label outside them is an error; without, the classes are
// those of the labels. Throws naming the file: a labelled file missing from `dir`, an unknown
// label, a recording that does not read.
LabelledRecordings read_labelled_recordings(const std::filesystem::path& dir,
                                            const std::filesystem::path& labels_path,
                                            const std::vector<std::string>& known_classes = {},
                                            int threads = 0);

// The inputs of read recordings. Throws naming the recording: no contact, contact too short
// for the windows.
LabelledInputs analyse_recordings(const LabelledRecordings& data,
                                  const RecordingInputOptions& options, int threads = 0);

// Both of the above.
LabelledInputs load_labelled_recordings(const std::filesystem::path& dir,
                                        const std::filesystem::path& labels_path,
                                        const RecordingInputOptions& options,
                                        const std::vector<std::string>& known_classes = {},
                                        int threads = 0);

// One set of options `classify train --select` compared, and how it scored: rows correct over
// the stratified folds of the training set (model_selection.hpp).
struct SelectionCandidate {
  RecordingInputOptions inputs;
  SvmOptions svm;
  int correct = 0, tested = 0;
  double accuracy() const { return tested ? static_cast<double>(correct) / tested : 0.0; }
};
struct SelectionRecord {
  int folds = 0;
  std::vector<SelectionCandidate> candidates;
  std::size_t chosen = 0;  // index in candidates: the model's options
};

struct ClassifierModel {
  int version = kClassifierModelVersion;
  RecordingInputOptions options;
  std::vector<std::string> input_names;
  std::vector<std::string> class_names;
  SvmOptions svm;
  MinMaxScaler scaler;  // of the training rows (what the SVC sees), for the record
  std::vector<std::string> files;
  SvmRows rows;
  std::vector<int> classes;
  std::vector<double> values;                // empty: no SVRs
  std::optional<SelectionRecord> selection;  // set when the options were chosen from the data
};

ClassifierModel make_classifier_model(const LabelledInputs& data, const SvmOptions& svm);

// The SVM settings `classify train --procedure NAME` uses unless told otherwise: the paper's
// (exponent 1, C = 1) for its scenes; for real slides ("stroke") C = 100, chosen with the inputs
// by `--select` (default_recording_inputs).
SvmOptions default_svm_options(RecordingProcedure procedure);

// What `classify train` and the Python module's train() take: every option left unset is the
// procedure's default (default_recording_inputs, default_svm_options), or with `select` searched
// (train_classifier in model_selection.hpp).
struct ClassifierTraining {
  RecordingProcedure procedure = RecordingProcedure::stroke;
  std::optional<ContactOptions::BaselineAt> baseline_at;
  std::optional<ContactOptions::Electrodes> electrodes;
  std::optional<double> trim;      // checked by check_trim_fraction
  std::vector<InputGroup> inputs;  // empty: the procedure's groups
  std::optional<int> kernel_degree;
  std::optional<double> c;
  bool select = false;  // choose every option left unset by cross-validation (--select)
  int cv_folds = 0;     // 0: none; K: also score by stratified K-fold (nested with select)
};
// Throw std::invalid_argument as check_trim_fraction.
RecordingInputOptions recording_inputs_for(const ClassifierTraining& training);
SvmOptions svm_options_for(const ClassifierTraining& training);
// A model of one class answers that class whatever it is given: not a classifier. Throws
// std::runtime_error naming the labels file and its classes when there are fewer than 2.
void require_two_classes(const std::vector<std::string>& class_names,
                         const std::filesystem::path& labels);

// Strict JSON; writing replaces the file only once it is complete. Reading throws
// tactile::FormatError naming the file: not JSON, another format version, a missing or
// mistyped field, inputs that differ from what this program computes for the stored procedure
// and groups, rows of the wrong length.
void write_classifier_model(const std::filesystem::path& path, const ClassifierModel& model);
ClassifierModel read_classifier_model(const std::filesystem::path& path);

struct ClassPrediction {
  int class_index = 0;
  double value = 0;  // from the SVR of the predicted class (0 without values)
};

// The fitted machines of a model.
class Classifier {
 public:
  explicit Classifier(const ClassifierModel& model);
  ClassPrediction predict(const std::vector<double>& inputs) const;
  bool has_values() const { return has_values_; }

 private:
  SvmModel svc_;
  std::vector<std::vector<SvmModel>> svr_;  // per class: empty or one SVR
  std::vector<double> class_value_;         // the value of a class with one distinct value
  bool has_values_ = false;
};

struct ClassifierTest {
  std::vector<ClassPrediction> predictions;  // per row of the test set
  std::vector<std::vector<int>> confusion;   // [true][predicted], classes of the model
  int correct = 0, tested = 0;
  double accuracy() const { return tested ? static_cast<double>(correct) / tested : 0.0; }
};
ClassifierTest test_classifier(const Classifier& classifier, std::size_t class_count,
                               const LabelledInputs& test);

// Stratified K-fold cross-validation: the rows of each class, in order, go to folds 0, 1, ...,
// K-1, 0, ...; each fold is tested on a model trained on the others. Throws
// std::invalid_argument when K is below 2 or above the rows of the largest class (folds would
// be empty).
struct CrossValidation {
  std::vector<double> fold_accuracy;
  double mean = 0, spread = 0;  // spread: sample standard deviation over folds
  int correct = 0, tested = 0;  // pooled
};
CrossValidation cross_validate(const LabelledInputs& data, const SvmOptions& svm, int folds,
                               int threads = 0);

// Throws std::invalid_argument (as cross_validate) for a fold count below 2 or above the rows
// of the largest class.
void check_fold_count(const std::vector<int>& classes, int folds);
// Accuracy per fold, mean, spread (sample standard deviation over folds) and pooled counts.
CrossValidation pool_folds(const std::vector<ClassifierTest>& folds);

// Fold of each row as cross_validate assigns them.
std::vector<int> stratified_folds(const std::vector<int>& classes, int folds);
// Rows of the smallest and of the largest class (0 without rows).
std::pair<int, int> class_sizes(const std::vector<int>& classes);

// Rows `keep` of a data set (e.g. trials 1-5 of every class).
LabelledInputs subset(const LabelledInputs& data, const std::vector<std::size_t>& keep);

}  // namespace tactile::perception
