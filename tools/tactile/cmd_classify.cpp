// `tactile classify`: train, test and use a classifier of labelled real recordings (e.g. the
// material under a BioTac sliding over it) with the paper's inputs and SVM conventions.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "request_options.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/classify_request.hpp"
#include "tactile/perception/model_selection.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/report.hpp"

namespace tactile::cli {
namespace {

// Whether training takes a default that was chosen from data: the slide defaults were chosen by
// --select on the project's 200 recordings, so plain cross-validation of them on those
// recordings scores the choice on the data it was made on.
bool uses_chosen_defaults(const perception::ClassifierTraining& t) {
  return t.procedure == perception::RecordingProcedure::stroke &&
         (t.inputs.empty() || !t.baseline_at || !t.electrodes || !t.trim || !t.kernel_degree ||
          !t.c);
}

int train(const perception::TrainRequest& o, const perception::ClassifierTraining& t) {
  const std::filesystem::path& out = *o.out;
  refuse_output_over_input(
      {output_file("--out", out)},
      perception::classify_inputs(o.recordings, o.labels, {}, OptionSpelling::cli));
  const auto t0 = std::chrono::steady_clock::now();
  const auto run = perception::train_classifier(o.recordings, o.labels, t, o.threads);
  const auto& model = run.model;
  if (t.select) {
    if (run.nested) {
      const auto& nested = *run.nested;
      fmt::print(
          "nested cross-validation ({} outer folds, stratified; options chosen in each by up to "
          "{}-fold cross-validation of its training rows among {} candidates): accuracy {:.3f} "
          "+- {:.3f} (folds: {:.3f}); pooled {}/{}\n",
          t.cv_folds, perception::kSelectionFolds, run.candidates, nested.outer.mean,
          nested.outer.spread, fmt::join(nested.outer.fold_accuracy, ", "), nested.outer.correct,
          nested.outer.tested);
      for (std::size_t k = 0; k < nested.chosen.size(); ++k)
        fmt::print("  fold {} chose {} (inner {:.3f})\n", k + 1,
                   perception::describe_candidate(nested.chosen[k]), nested.chosen[k].accuracy());
    }
    const auto& record = *model.selection;
    const auto& chosen = record.candidates.at(record.chosen);
    fmt::print("classify train --select: {} recordings, {} classes; chose {} ({}-fold CV {:.3f})\n",
               model.files.size(), model.class_names.size(), perception::describe_candidate(chosen),
               record.folds, chosen.accuracy());
  } else {
    const auto& in = model.options;
    fmt::print(
        "classify train: {} recordings, {} classes, {} inputs ({} as {}; baseline {}, "
        "electrodes {}, trim {:g}), analysed in {:.2f} s\n",
        model.rows.size(), model.class_names.size(), model.input_names.size(),
        fmt::join(names_of(in.groups), ","), to_string(t.procedure),
        to_string(in.contact.baseline_at), to_string(in.contact.electrodes),
        in.contact.trim_fraction, run.analysis_s);
    if (run.cv) {
      const auto& cv = *run.cv;
      fmt::print(
          "cross-validation ({} folds, stratified): accuracy {:.3f} +- {:.3f} (folds: {:.3f}); "
          "pooled {}/{}\n",
          t.cv_folds, cv.mean, cv.spread, fmt::join(cv.fold_accuracy, ", "), cv.correct, cv.tested);
      if (uses_chosen_defaults(t))
        fmt::print(
            "  (plain cross-validation of fixed options. The stroke defaults were chosen by "
            "nested cross-validation on the project's 200 recordings of 20 materials "
            "(docs/perception-models.md): on other recordings this is an estimate for them; on "
            "those 200 it carries the choice and overstates, and the estimate is nested: "
            "`classify train --select --cv {}`)\n",
            t.cv_folds);
    }
  }
  perception::write_classifier_model(out, model);
  fmt::print(
      "classify train: SVC (polynomial kernel, exponent {}, C = {:g}){}; accuracy on the "
      "training set {}/{}; model -> {} ({:.2f} s in all)\n",
      model.svm.degree, model.svm.c,
      model.values.empty() ? "" : " and one SVR per class for the value", run.training_fit.correct,
      run.training_fit.tested, out.string(), seconds_since(t0));
  return 0;
}

int test(const perception::TestRequest& request) {
  const std::filesystem::path& model_path = request.model;
  const std::filesystem::path& recordings = request.recordings;
  const std::filesystem::path& labels = request.labels;
  const std::filesystem::path csv_dir = request.csv.value_or(std::filesystem::path());
  const int threads = request.threads;
  if (!csv_dir.empty()) {
    refuse_output_over_input(
        {output_folder("--csv", csv_dir, perception::kTestReportFiles)},
        perception::classify_inputs(recordings, labels, model_path, OptionSpelling::cli));
  }
  const auto model = perception::read_classifier_model(model_path);
  const perception::Classifier fitted(model);
  const auto data = perception::load_labelled_recordings(recordings, labels, model.options,
                                                         model.class_names, threads);
  const auto t = perception::test_classifier(fitted, model.class_names.size(), data);
  const bool values = fitted.has_values() && !data.values.empty();
  for (const auto& line : perception::confusion_lines(model.class_names, t.confusion))
    fmt::print("{}\n", line);
  if (values) {
    double ss = 0;
    for (std::size_t i = 0; i < data.rows.size(); ++i)
      ss += std::pow(t.predictions[i].value - data.values[i], 2);
    fmt::print("value: RMS error {:.4g} (SVR of the predicted class)\n",
               std::sqrt(ss / static_cast<double>(data.rows.size())));
  }
  fmt::print("accuracy {:.3f} ({}/{})\n", t.accuracy(), t.correct, t.tested);
  if (!csv_dir.empty()) {
    perception::write_test_report(csv_dir, model.class_names, data, t, values);
    fmt::print(
        "classify test: confusion.csv, confusion.svg, confusion.png, predictions.csv -> {}\n",
        csv_dir.string());
  }
  return 0;
}

int predict(const std::filesystem::path& model_path,
            const std::vector<std::filesystem::path>& files) {
  const auto model = perception::read_classifier_model(model_path);
  const perception::Classifier fitted(model);
  int failed = 0;
  for (const auto& f : files) {
    try {
      const auto p = fitted.predict(
          perception::recording_inputs(perception::read_sensor_csv(f), model.options));
      const auto& name = model.class_names.at(static_cast<std::size_t>(p.class_index));
      if (fitted.has_values())
        fmt::print("{}: {} value {:.6g}\n", f.string(), name, p.value);
      else
        fmt::print("{}: {}\n", f.string(), name);
    } catch (const std::exception& e) {
      ++failed;
      fmt::print(stderr, "tactile classify predict: {}\n", e.what());
    }
  }
  return failed ? 1 : 0;
}

}  // namespace

void add_classify(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  CLI::App* sub = app.add_subcommand(
      "classify",
      "Classifier of labelled real recordings (BioTac-style CSV, one per trial) with the paper's\n"
      "inputs and conventions: WEKA [0, 1] scaling, polynomial-kernel SVC (C = 1; 100 for "
      "slides);\n"
      "with a numeric `value` column in the labels, also one SVR per class for the value.");
  sub->require_subcommand(1);

  const auto [t, tr] = add_request_command<perception::TrainRequest>(
      *sub, "train",
      "Analyse labelled recordings, train, write a model file (optionally cross-validate)",
      perception::train_options());
  // Python may keep the model in memory; the command line has nowhere else to put it.
  tr->get_option("--out")->required();
  tr->callback([t, &action] {
    const perception::ClassifierTraining training = perception::resolve(*t, OptionSpelling::cli);
    action = [t, training] { return train(*t, training); };
  });

  const auto [te, ts] = add_request_command<perception::TestRequest>(
      *sub, "test",
      "Accuracy of a model on labelled recordings: per class, overall, confusion matrix",
      perception::test_options());
  ts->callback([te, &action] {
    perception::check_request(*te, OptionSpelling::cli);
    action = [te] { return test(*te); };
  });

  struct PredictOptions {
    std::filesystem::path model;
    std::vector<std::filesystem::path> files;
  };
  const auto [pr, ps] =
      add_own_command<PredictOptions>(*sub, "predict", "Class (and value) of each recording");
  add_input_file(*ps, "--model", pr->model, "Model file from `classify train`");
  // Named as `--help` shows it, so that "RECORDINGS is required" says what is missing.
  ps->add_option("RECORDINGS", pr->files, "Recordings (BioTac-style CSV files)")->required();
  ps->callback([pr, &action] { action = [pr] { return predict(pr->model, pr->files); }; });
}

}  // namespace tactile::cli
