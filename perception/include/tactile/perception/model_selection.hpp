#pragma once
// Choosing a classifier's options from the data without scoring the choice on the same data.
//
// Every option of the analysis and of the SVM that could be set by looking at accuracy (input
// groups, baseline, electrodes, trim, kernel exponent, C) is a dimension of a grid. The
// selection scores every candidate by stratified K-fold cross-validation on the training rows
// and keeps the best; nested cross-validation repeats that selection inside each outer training
// fold and scores the chosen candidate on the outer test fold, so its figure is of the whole
// procedure (choice included) on rows the choice never saw.
//
// Ties (equal rows correct) go to the simpler candidate: fewer inputs, then the lower kernel
// exponent, then C nearer 1, then grid order. Scored by class accuracy only; a value column's
// SVRs follow the chosen options.

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "tactile/perception/classifier_model.hpp"

namespace tactile::perception {

struct SelectionGrid {
  std::vector<std::vector<InputGroup>> input_sets;
  std::vector<ContactOptions::BaselineAt> baselines;
  std::vector<ContactOptions::Electrodes> electrodes;
  std::vector<double> trims;
  std::vector<int> degrees;
  std::vector<double> cs;
  std::size_t size() const {
    return input_sets.size() * baselines.size() * electrodes.size() * trims.size() *
           degrees.size() * cs.size();
  }
};

// What `classify train --select` compares for a procedure ("stroke", "static", "dp", "ru",
// "roll"): the plain statistics, the paper's groups and combinations of the two (means and bands,
// the paper's with stats); baseline none or at the end (recordings that begin in contact have no
// free air at the start); clusters or each electrode; trim 0, 0.1, 0.2 (strokes); exponent 1 or
// 2; C 0.01, 0.1, 1, 10, 100, 1000 (a choice at either end would say the range is too narrow).
SelectionGrid default_selection_grid(RecordingProcedure procedure);

// The candidate with the most rows correct over `folds` stratified folds of `rows` (all rows
// when empty), every candidate of the grid scored; the record's candidates are in grid order.
// `folds` is lowered to the smallest class's rows when that is fewer. Throws
// std::invalid_argument when a class has fewer than 2 rows (nothing to cross-validate), and
// std::runtime_error naming a recording that cannot be analysed with a candidate's options.
SelectionRecord select_options(const LabelledRecordings& data, const RecordingInputOptions& base,
                               const SelectionGrid& grid, int folds,
                               const std::vector<std::size_t>& rows = {}, int threads = 0);

// The model of the chosen candidate on all rows, the selection recorded in it.
ClassifierModel make_selected_model(const LabelledRecordings& data, const SelectionRecord& record,
                                    int threads = 0);

// Nested cross-validation: `outer_folds` stratified folds score the selection (with
// `inner_folds` inside each outer training fold). Also the candidate each fold chose, and the
// selection on all rows (what select_options gives), from the same analysis.
struct NestedCrossValidation {
  CrossValidation outer;
  std::vector<SelectionCandidate> chosen;  // per outer fold, with its inner score
  SelectionRecord overall;
};
NestedCrossValidation nested_cross_validate(const LabelledRecordings& data,
                                            const RecordingInputOptions& base,
                                            const SelectionGrid& grid, int outer_folds,
                                            int inner_folds, int threads = 0);

// Folds of the selection by cross-validation (`classify train --select`), and the inner folds
// of a nested cross-validation.
inline constexpr int kSelectionFolds = 5;

// The procedure's grid (default_selection_grid) with every option `training` names fixed to
// that value.
SelectionGrid selection_grid_for(const ClassifierTraining& training);

// A training as `classify train` runs it, and what it reports.
struct ClassifierTrainingRun {
  ClassifierModel model;              // with select, the selection recorded in it (model.selection)
  double analysis_s = 0;              // reading and analysing the recordings (without select)
  std::size_t candidates = 0;         // select: the grid's size
  std::optional<CrossValidation> cv;  // cv_folds without select
  std::optional<NestedCrossValidation> nested;  // cv_folds with select
  ClassifierTest training_fit;                  // the model on its own training rows
};
// Reads and analyses the labelled recordings, with training.select chooses the options left
// unset (kSelectionFolds-fold cross-validation), with cv_folds scores the training by
// cross-validation (nested with select), and trains the model on every recording. Throws as
// load_labelled_recordings, require_two_classes (fewer than 2 classes), select_options and
// cross_validate (std::invalid_argument for a fold count below 2 or above a class's rows).
ClassifierTrainingRun train_classifier(const std::filesystem::path& recordings,
                                       const std::filesystem::path& labels,
                                       const ClassifierTraining& training, int threads = 0);

// "stats; baseline none, electrodes each, trim 0.1; exponent 1, C = 1" (for messages).
std::string describe_candidate(const SelectionCandidate& c);

}  // namespace tactile::perception
