#pragma once
// `classify train` and `classify test` as requests: what a person asks of training or testing a
// classifier of labelled recordings, their option tables (read by the command line and the
// Python module alike) and resolve(), which holds the rules (a trim a contact can have, a
// procedure's inputs). The defaults per procedure are ClassifierTraining's (recording_inputs_for,
// svm_options_for); the rest are the member initialisers below.

#include <filesystem>
#include <optional>
#include <vector>

#include "tactile/common/option_table.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/perception/classifier_model.hpp"

namespace tactile::perception {

struct TrainRequest {
  std::filesystem::path recordings;          // a folder of recordings
  std::filesystem::path labels;              // file,class[,value]
  std::optional<std::filesystem::path> out;  // the model file (the command line needs one)
  ClassifierTraining training;               // unset options: the procedure's defaults
  std::optional<int> cv;                     // stratified K-fold scoring; unset: none
  int threads = 0;                           // 0: all cores
};

const std::vector<OptionRow<TrainRequest>>& train_options();

// Every value against its row, then the procedure's rules (check_trim_fraction, the groups a
// procedure has): RequestError in the front end's spelling, before any recording is read.
ClassifierTraining resolve(const TrainRequest& request, OptionSpelling spelling);

struct TestRequest {
  std::filesystem::path model;  // the command line's model file (Python may pass the model)
  std::filesystem::path recordings;
  std::filesystem::path labels;
  // The confusion matrix (CSV, SVG, PNG) and the predictions per file; unset: none.
  std::optional<std::filesystem::path> csv;
  int threads = 0;
};

const std::vector<OptionRow<TestRequest>>& test_options();

// Every value against its row (RequestError).
void check_request(const TestRequest& request, OptionSpelling spelling);

// The inputs an output must not name: the labels file, every file in the recordings folder (the
// labels choose among them; any may be read) and, when given, the model file; named in the
// front end's spelling.
std::vector<NamedPath> classify_inputs(const std::filesystem::path& recordings,
                                       const std::filesystem::path& labels,
                                       const std::filesystem::path& model, OptionSpelling spelling);

}  // namespace tactile::perception
