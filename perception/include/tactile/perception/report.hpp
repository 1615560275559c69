#pragma once
// Files of the perception evaluation (docs/formats.md, "Perception results"): Table 2 as CSV
// (one row per input set and kernel: accuracy, confusion matrix, R^2 and RMS error per
// curvature), Figure 7 as CSV (every held-out prediction) and as charts, SVG and PNG (predicted
// against true signed footprint, one colour per curvature), and the classifier's accuracy per
// footprint (where it fails is as telling as how often).

#include <filesystem>
#include <string>
#include <vector>

#include "tactile/common/chart.hpp"
#include "tactile/perception/cascade.hpp"
#include "tactile/perception/classifier_model.hpp"

namespace tactile::perception {

struct TimedCascade {
  CascadeResult result;
  double train_test_s = 0;  // training and testing every model of this row
};

// Every row of Table 2: each input set (all, static, dp, ru, roll) with each kernel exponent
// (the paper: 1 and 2).
std::vector<TimedCascade> run_table2(const PerceptionDataset& d, const PerceptionSplit& split,
                                     const std::vector<int>& degrees = {1, 2});

void write_table2_csv(const std::filesystem::path& path, const std::vector<TimedCascade>& rows);
void write_figure7_csv(const std::filesystem::path& path, const std::vector<TimedCascade>& rows);
// Figure 7 of one row: predicted against true signed footprint, one colour per curvature class,
// as PATH with .svg and .png (common/chart.hpp).
ChartFiles write_figure7_chart(const std::filesystem::path& path, const CascadeResult& result);

// Held-out curvature accuracy of one row per signed footprint, ordered by footprint.
struct FootprintAccuracy {
  double footprint_mm = 0;  // signed: + bump, - pit
  int correct = 0, tested = 0;
};
std::vector<FootprintAccuracy> accuracy_by_footprint(const CascadeResult& result);

// CSV `inputs,degree,footprint_mm,correct,tested,accuracy` for every row, and a chart (.svg and
// .png) of the rows with kernel exponent `degree`: accuracy against footprint, one line per
// input set.
void write_accuracy_by_footprint_csv(const std::filesystem::path& path,
                                     const std::vector<TimedCascade>& rows);
ChartFiles write_accuracy_by_footprint_chart(const std::filesystem::path& path,
                                             const std::vector<TimedCascade>& rows, int degree);

// A confusion matrix as a chart (.svg and .png): one cell per (true, predicted) class, shaded by
// the share of the true class's recordings, with the count written in it.
ChartFiles write_confusion_chart(const std::filesystem::path& path,
                                 const std::vector<std::string>& class_names,
                                 const std::vector<std::vector<int>>& confusion);

// An order of the classes of a square confusion matrix [true][predicted] that puts classes
// confused with each other next to each other, so that errors sit near the diagonal: greedy
// seriation on the symmetric confusion (errors either way): start from the most confused pair,
// attach at either end of the chain the class most confused with that end, start a new chain
// when none is; classes never confused with another come last, in their given order.
std::vector<std::size_t> confusion_order(const std::vector<std::vector<int>>& confusion);

// `dir`/confusion.csv (`true\predicted,NAME,...`, one row per true class) and
// `dir`/confusion.svg and .png, rows and columns in confusion_order.
void write_confusion_report(const std::filesystem::path& dir,
                            const std::vector<std::string>& class_names,
                            const std::vector<std::vector<int>>& confusion);

// `path` (`file,class,predicted,correct` and, `with_values`, `value,predicted_value`): one row
// per tested recording of `data`, its prediction in `test` (same order), classes named by
// `class_names` (the model's).
void write_predictions_csv(const std::filesystem::path& path,
                           const std::vector<std::string>& class_names, const LabelledInputs& data,
                           const ClassifierTest& test, bool with_values);

// The files of a test's report (`classify test --csv`), in `dir`.
inline const std::vector<std::filesystem::path> kTestReportFiles = {
    "confusion.csv", "confusion.svg", "confusion.png", "predictions.csv"};

// write_confusion_report and write_predictions_csv into `dir`: the four files describe one test,
// replaced together or not at all.
void write_test_report(const std::filesystem::path& dir,
                       const std::vector<std::string>& class_names, const LabelledInputs& data,
                       const ClassifierTest& test, bool with_values);

// One line per true class that was tested, for the terminal: its correct count and the classes
// it was taken for, e.g. "oak: 8/10 correct; taken for pine 2".
std::vector<std::string> confusion_lines(const std::vector<std::string>& class_names,
                                         const std::vector<std::vector<int>>& confusion);

// One line per row of Table 2, for the terminal.
std::string table2_line(const TimedCascade& row);

// Where a row's classifier errs, for the terminal: how many held-out trials it gives the wrong
// curvature, and of those per footprint (bumps and pits together), largest share first, e.g.
// "all exp 1: curvature wrong on 14 of 96: 1.25 mm 8 of 12, 2.5 mm 4 of 12, 5 mm 2 of 12".
std::string misclassified_line(const CascadeResult& result);

}  // namespace tactile::perception
