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
#include "mode_option.hpp"
#include "number_checks.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/model_selection.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/report.hpp"

namespace tactile::cli {
namespace {

// The labels file, every file in the recordings folder (the labels choose among them; any may
// be read) and, when given, the model.
std::vector<NamedPath> classify_inputs(const std::filesystem::path& recordings,
                                       const std::filesystem::path& labels,
                                       const std::filesystem::path& model = {}) {
  std::vector<NamedPath> inputs = {{"--labels", labels}};
  if (!model.empty()) inputs.push_back({"--model", model});
  std::error_code ec;
  const auto options = std::filesystem::directory_options::skip_permission_denied;
  for (auto it = std::filesystem::recursive_directory_iterator(recordings, options, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_directory(ec)) inputs.push_back({"--recordings", it->path()});
  }
  return inputs;
}

struct TrainOptions {
  std::filesystem::path recordings, labels, out;
  // Options unset: the procedure's defaults, or searched with --select.
  perception::ClassifierTraining training;
  int threads = 0;
};

// Whether training takes a default that was chosen from data: the slide defaults were chosen by
// --select on the project's 200 recordings, so plain cross-validation of them on those
// recordings scores the choice on the data it was made on.
bool uses_chosen_defaults(const perception::ClassifierTraining& t) {
  return t.procedure == perception::RecordingProcedure::stroke &&
         (t.inputs.empty() || !t.baseline_at || !t.electrodes || !t.trim || !t.kernel_degree ||
          !t.c);
}

int train(const TrainOptions& o) {
  refuse_output_over_input({output_file("--out", o.out)}, classify_inputs(o.recordings, o.labels));
  const auto t0 = std::chrono::steady_clock::now();
  const perception::ClassifierTraining& t = o.training;
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
  perception::write_classifier_model(o.out, model);
  fmt::print(
      "classify train: SVC (polynomial kernel, exponent {}, C = {:g}){}; accuracy on the "
      "training set {}/{}; model -> {} ({:.2f} s in all)\n",
      model.svm.degree, model.svm.c,
      model.values.empty() ? "" : " and one SVR per class for the value", run.training_fit.correct,
      run.training_fit.tested, o.out.string(), seconds_since(t0));
  return 0;
}

int test(const std::filesystem::path& model_path, const std::filesystem::path& recordings,
         const std::filesystem::path& labels, const std::filesystem::path& csv_dir, int threads) {
  if (!csv_dir.empty()) {
    refuse_output_over_input(
        {output_folder("--csv", csv_dir,
                       {"confusion.csv", "confusion.svg", "confusion.png", "predictions.csv"})},
        classify_inputs(recordings, labels, model_path));
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
    // The four files describe one test: replaced together or not at all.
    CommitTogether together;
    perception::write_confusion_report(csv_dir, model.class_names, t.confusion);
    perception::write_predictions_csv(csv_dir / "predictions.csv", model.class_names, data, t,
                                      values);
    together.commit();
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

void add_classify(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "classify",
      "Classifier of labelled real recordings (BioTac-style CSV, one per trial) with the paper's\n"
      "inputs and conventions: WEKA [0, 1] scaling, polynomial-kernel SVC (C = 1; 100 for "
      "slides);\n"
      "with a numeric `value` column in the labels, also one SVR per class for the value.");
  sub->require_subcommand(1);

  auto t = std::make_shared<TrainOptions>();
  CLI::App* tr = sub->add_subcommand(
      "train",
      "Analyse labelled recordings, train, write a model file (optionally cross-validate)");
  tr->add_option("--recordings", t->recordings, "Folder of the recordings")
      ->required()
      ->check(CLI::ExistingDirectory);
  tr->add_option("--labels", t->labels, "Labels CSV: file,class[,value]")
      ->required()
      ->check(CLI::ExistingFile);
  tr->add_option("--out", t->out, "Model file to write (JSON)")->required();
  add_mode_option(*tr, "--procedure", t->training.procedure, perception::kRecordingProcedureNames,
                  "What a recording is: stroke (a slide over a texture), static (a press), or a "
                  "scene of the paper: dp, ru, roll (feature contact from its kinematics)");
  add_optional_mode_option(
      *tr, "--baseline-at", t->training.baseline_at, perception::kBaselineAtNames,
      "Where the free-air baseline is: end (recordings that begin in contact), start, "
      "or none (the recording software already subtracted one); default: none for "
      "stroke, end otherwise");
  add_optional_mode_option(
      *tr, "--electrodes", t->training.electrodes, perception::kElectrodesNames,
      "Electrode signals of the inputs: clusters (the paper's 6 cluster means) or each "
      "(all 19 electrodes); default: clusters");
  tr->add_option("--trim", t->training.trim,
                 "Strokes: fraction of the contact left out at each end, in [0, 0.5) (the press "
                 "and the lift of a slide); default: 0.2 for stroke, 0 otherwise")
      ->check(CLI::Validator(
          [](std::string& text) {
            double fraction = 0;
            try {
              fraction = std::stod(text);
            } catch (const std::out_of_range&) {
              return text + " is not a finite number";
            } catch (const std::exception&) {
              return std::string();  // not a number: the conversion reports it
            }
            if (!std::isfinite(fraction)) return text + " is not a finite number";
            try {
              perception::check_trim_fraction(fraction);
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "in [0, 0.5)"));
  add_mode_list_option(
      *tr, "--inputs", t->training.inputs, perception::kInputGroupNames,
      "Input groups, comma-separated: means, rates, hht (the paper's), bands (octave "
      "band powers of the vibration), stds (standard deviation of each signal over the "
      "contact), stats (plain statistics: mean and standard deviation of each signal, "
      "the vibration's, and the bands); default: stroke means,bands; dp, ru, roll the "
      "paper's means,rates,hht; static means");
  tr->add_option("--kernel-degree", t->training.kernel_degree,
                 "Exponent of the polynomial kernel; default 1 (searched with --select)")
      ->check(CLI::IsMember({1, 2}));
  tr->add_option(
        "--c", t->training.c,
        "SVM complexity constant C; default: 100 for stroke, 1 otherwise (searched with --select)")
      ->check(within(0.001, 100000.0));
  tr->add_option("--cv", t->training.cv_folds,
                 "Also report stratified K-fold cross-validation accuracy: of the options as given "
                 "(the stroke defaults were chosen on the project's recordings: on those, use "
                 "--select), or with --select nested, the choice made again inside each fold")
      ->check(CLI::Range(2, 1000));
  tr->add_flag("--select", t->training.select,
               "Choose every option not given (inputs, baseline, electrodes, trim, kernel "
               "exponent, C) by 5-fold cross-validation on these recordings; the model records "
               "the comparison");
  tr->add_option("--threads", t->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 256));
  tr->callback([t, &action] { action = [t] { return train(*t); }; });

  struct TestOptions {
    std::filesystem::path model, recordings, labels, csv;
    int threads = 0;
  };
  auto te = std::make_shared<TestOptions>();
  CLI::App* ts = sub->add_subcommand(
      "test", "Accuracy of a model on labelled recordings: per class, overall, confusion matrix");
  ts->add_option("--model", te->model, "Model file from `classify train`")
      ->required()
      ->check(CLI::ExistingFile);
  ts->add_option("--recordings", te->recordings, "Folder of the recordings")
      ->required()
      ->check(CLI::ExistingDirectory);
  ts->add_option("--labels", te->labels, "Labels CSV: file,class[,value]")
      ->required()
      ->check(CLI::ExistingFile);
  ts->add_option(
      "--csv", te->csv,
      "Folder for confusion.csv, confusion.svg, confusion.png and predictions.csv (created if "
      "missing)");
  ts->add_option("--threads", te->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 256));
  ts->callback([te, &action] {
    action = [te] { return test(te->model, te->recordings, te->labels, te->csv, te->threads); };
  });

  struct PredictOptions {
    std::filesystem::path model;
    std::vector<std::filesystem::path> files;
  };
  auto pr = std::make_shared<PredictOptions>();
  CLI::App* ps = sub->add_subcommand("predict", "Class (and value) of each recording");
  ps->add_option("--model", pr->model, "Model file from `classify train`")
      ->required()
      ->check(CLI::ExistingFile);
  ps->add_option("files", pr->files, "Recordings (BioTac-style CSV)")->required();
  ps->callback([pr, &action] { action = [pr] { return predict(pr->model, pr->files); }; });
}

}  // namespace tactile::cli
