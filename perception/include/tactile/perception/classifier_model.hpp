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
#include <string>
#include <vector>

#include "tactile/perception/recording_inputs.hpp"
#include "tactile/perception/svm_model.hpp"

namespace tactile::perception {

// Version 2 added contact.trim_fraction and contact.electrodes; version 1 files are still read.
inline constexpr int kClassifierModelVersion = 2;

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

// Reads and analyses every recording the labels name, in `dir`, on `threads` workers (0: all
// cores). With `known_classes` (testing a model), a label outside them is an error; without,
// the classes are those of the labels. Throws naming the file: a labelled file missing from
// `dir`, an unknown label, a recording with no contact or too short for the windows.
LabelledInputs load_labelled_recordings(const std::filesystem::path& dir,
                                        const std::filesystem::path& labels_path,
                                        const RecordingInputOptions& options,
                                        const std::vector<std::string>& known_classes = {},
                                        int threads = 0);

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
  std::vector<double> values;  // empty: no SVRs
};

ClassifierModel make_classifier_model(const LabelledInputs& data, const SvmOptions& svm);

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
// K-1, 0, ...; each fold is tested on a model trained on the others.
struct CrossValidation {
  std::vector<double> fold_accuracy;
  double mean = 0, spread = 0;  // spread: sample standard deviation over folds
  int correct = 0, tested = 0;  // pooled
};
CrossValidation cross_validate(const LabelledInputs& data, const SvmOptions& svm, int folds,
                               int threads = 0);

// Rows `keep` of a data set (e.g. trials 1-5 of every class).
LabelledInputs subset(const LabelledInputs& data, const std::vector<std::size_t>& keep);

}  // namespace tactile::perception
