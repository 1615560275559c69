// The classifier of labelled recordings: train, test, predict, as `tactile classify` (the same
// defaults per procedure, perception::ClassifierTraining), the model a Python object that can be
// written to and read from the model file.

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <variant>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/classify_request.hpp"
#include "tactile/perception/model_selection.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/report.hpp"

namespace tactile::python {

namespace {

namespace fs = std::filesystem;
using perception::ClassifierModel;
using ModelArgument = std::variant<std::shared_ptr<ClassifierModel>, fs::path>;

std::shared_ptr<ClassifierModel> model_argument(const ModelArgument& model) {
  if (const auto* m = std::get_if<std::shared_ptr<ClassifierModel>>(&model)) return *m;
  const fs::path& path = std::get<fs::path>(model);
  return std::make_shared<ClassifierModel>(
      with_inputs({path}, [&] { return perception::read_classifier_model(path); }));
}

// The options a model's rows were analysed with, and its SVM's, by the names the command line
// takes.
void put_options(py::dict& out, const perception::RecordingInputOptions& in,
                 const perception::SvmOptions& svm) {
  out["inputs"] = names_of(in.groups);
  out["baseline_at"] = perception::to_string(in.contact.baseline_at);
  out["electrodes"] = perception::to_string(in.contact.electrodes);
  out["trim"] = in.contact.trim_fraction;
  out["kernel_degree"] = svm.degree;
  out["c"] = svm.c;
}

py::dict candidate_dict(const perception::SelectionCandidate& c) {
  py::dict out;
  put_options(out, c.inputs, c.svm);
  out["correct"] = c.correct;
  out["tested"] = c.tested;
  out["accuracy"] = c.accuracy();
  out["description"] = perception::describe_candidate(c);
  return out;
}

py::dict cv_dict(const perception::CrossValidation& cv, int folds) {
  py::dict out;
  out["folds"] = folds;
  out["fold_accuracy"] = cv.fold_accuracy;
  out["mean"] = cv.mean;
  out["spread"] = cv.spread;  // sample standard deviation over folds
  out["correct"] = cv.correct;
  out["tested"] = cv.tested;
  return out;
}

// What `classify train --select` compared (the model file's `selection`); None without.
py::object selection_dict(const ClassifierModel& model) {
  if (!model.selection) return py::none();
  const auto& record = *model.selection;
  py::dict out;
  out["folds"] = record.folds;
  py::list candidates;
  for (const auto& c : record.candidates) candidates.append(candidate_dict(c));
  out["candidates"] = candidates;
  out["chosen"] = record.chosen;  // index in candidates
  return out;
}

// What `classify train` prints, as data.
py::dict report_dict(const perception::ClassifierTrainingRun& run,
                     const perception::ClassifierTraining& training) {
  const auto& m = run.model;
  py::dict out;
  out["recordings"] = m.files.size();
  out["class_names"] = m.class_names;
  out["procedure"] = perception::to_string(training.procedure);
  put_options(out, m.options, m.svm);
  out["input_count"] = m.input_names.size();
  out["values"] = !m.values.empty();  // one SVR per class for the value
  out["training_correct"] = run.training_fit.correct;
  out["training_tested"] = run.training_fit.tested;
  if (!training.select) out["analysis_s"] = run.analysis_s;
  out["selection"] = selection_dict(m);
  if (run.cv) {
    py::dict cv = cv_dict(*run.cv, training.cv_folds);
    cv["nested"] = false;
    out["cv"] = cv;
  } else if (run.nested) {
    py::dict cv = cv_dict(run.nested->outer, training.cv_folds);
    cv["nested"] = true;
    cv["inner_folds"] = perception::kSelectionFolds;
    cv["candidates"] = run.candidates;
    py::list chosen;
    for (const auto& c : run.nested->chosen) chosen.append(candidate_dict(c));
    cv["chosen"] = chosen;  // per outer fold, scored on its training rows
    out["cv"] = cv;
  } else {
    out["cv"] = py::none();
  }
  return out;
}

py::object train(const fs::path& recordings, const fs::path& labels, const py::kwargs& kwargs) {
  perception::TrainRequest request;
  request.recordings = recordings;
  request.labels = labels;
  set_from_kwargs(request, perception::train_options(), kwargs, "train");
  // Checked before any recording is read, as on the command line.
  const perception::ClassifierTraining training =
      perception::resolve(request, OptionSpelling::python);
  const int threads = request.threads;
  const std::optional<fs::path>& out = request.out;
  perception::ClassifierTrainingRun run;
  {
    py::gil_scoped_release unlocked;
    run = with_inputs({recordings, labels}, [&] {
      return perception::train_classifier(recordings, labels, training, threads);
    });
    if (out) perception::write_classifier_model(*out, run.model);
  }
  py::object model = py::cast(std::make_shared<ClassifierModel>(run.model));
  model.attr("report") = report_dict(run, training);
  return model;
}

py::dict test(const ModelArgument& model_arg, const fs::path& recordings, const fs::path& labels,
              const py::kwargs& kwargs) {
  perception::TestRequest request;
  request.recordings = recordings;
  request.labels = labels;
  set_from_kwargs(request, perception::test_options(), kwargs, "test");
  perception::check_request(request, OptionSpelling::python);
  const int threads = request.threads;
  if (request.csv) {
    const auto* path = std::get_if<fs::path>(&model_arg);
    refuse_output_over_input(
        {output_folder("csv", *request.csv, perception::kTestReportFiles)},
        perception::classify_inputs(recordings, labels, path ? *path : fs::path(),
                                    OptionSpelling::python));
  }
  const auto model = model_argument(model_arg);
  perception::ClassifierTest t;
  perception::LabelledInputs data;
  {
    py::gil_scoped_release unlocked;
    const perception::Classifier fitted(*model);
    data = with_inputs({recordings, labels}, [&] {
      return perception::load_labelled_recordings(recordings, labels, model->options,
                                                  model->class_names, threads);
    });
    t = perception::test_classifier(fitted, model->class_names.size(), data);
    if (request.csv) {
      perception::write_test_report(*request.csv, model->class_names, data, t,
                                    fitted.has_values() && !data.values.empty());
    }
  }
  const auto n = static_cast<py::ssize_t>(model->class_names.size());
  py::array_t<int> confusion({n, n});
  auto cm = confusion.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i)
    for (py::ssize_t j = 0; j < n; ++j)
      cm(i, j) = t.confusion[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  py::list predicted;
  for (const auto& p : t.predictions) {
    predicted.append(model->class_names.at(static_cast<std::size_t>(p.class_index)));
  }
  py::dict out;
  out["accuracy"] = t.accuracy();
  out["correct"] = t.correct;
  out["tested"] = t.tested;
  out["class_names"] = model->class_names;
  out["confusion"] = confusion;  // [true][predicted]
  out["files"] = data.files;
  out["predicted"] = predicted;
  return out;
}

py::list predict(const ModelArgument& model_arg, const std::vector<fs::path>& files) {
  const auto model = model_argument(model_arg);
  const perception::Classifier fitted(*model);
  py::list out;
  for (const auto& f : files) {
    const auto p = with_inputs({f}, [&] {
      return fitted.predict(
          perception::recording_inputs(perception::read_sensor_csv(f), model->options));
    });
    const auto& name = model->class_names.at(static_cast<std::size_t>(p.class_index));
    out.append(fitted.has_values() ? py::make_tuple(name, p.value)
                                   : py::make_tuple(name, py::none()));
  }
  return out;
}

}  // namespace

void bind_classifier(py::module_& m) {
  py::class_<ClassifierModel, std::shared_ptr<ClassifierModel>>(
      m, "ClassifierModel",
      "A trained classifier of labelled recordings (its model file). A model from train() also\n"
      "has `report`: what `classify train` prints, as a dict.",
      py::dynamic_attr())
      .def_readonly("class_names", &ClassifierModel::class_names)
      .def_readonly("input_names", &ClassifierModel::input_names)
      .def_readonly("files", &ClassifierModel::files)
      .def_property_readonly("kernel_degree", [](const ClassifierModel& c) { return c.svm.degree; })
      .def_property_readonly("c", [](const ClassifierModel& c) { return c.svm.c; })
      .def_property_readonly("selection", &selection_dict,
                             "What `classify train --select` compared (folds, candidates, chosen "
                             "index), None when the options were not chosen from the data")
      .def(
          "write",
          [](const ClassifierModel& c, const fs::path& path) {
            perception::write_classifier_model(path, c);
          },
          py::arg("path"));
  m.def(
      "read_classifier_model", [](const fs::path& path) { return model_argument(path); },
      py::arg("path"));
  def_with_kwargs(
      m, "train", &train, perception::train_options(),
      "Trains a classifier of the labelled recordings (labels CSV file,class[,value]) as\n"
      "`tactile classify train`: options left unset are the procedure's defaults (stroke,\n"
      "static, dp, ru, roll), or with select=True chosen by 5-fold cross-validation on these\n"
      "recordings (`--select`; the comparison recorded in the model); cv=K also scores it by\n"
      "stratified K-fold cross-validation (`--cv K`; nested with select, the choice made again\n"
      "inside each fold). Writes the model file when `out` is given. The model's `report` is\n"
      "what the command prints: recordings, class_names, the options used (inputs,\n"
      "baseline_at, electrodes, trim, kernel_degree, c), training_correct/_tested, `cv` (folds,\n"
      "fold_accuracy, mean, spread, correct, tested, nested; with select also inner_folds,\n"
      "candidates and the candidate each fold chose) and `selection` (folds, candidates with\n"
      "their accuracy, chosen index), each None when not asked for. Keywords (the command\n"
      "line's options, with underscores; inputs also as a list):",
      py::arg("recordings"), py::arg("labels"));
  def_with_kwargs(
      m, "test", &test, perception::test_options(),
      "Accuracy of a model (a ClassifierModel or its file) on labelled recordings: accuracy,\n"
      "correct, tested, class_names, confusion [true][predicted], files, predicted; with csv,\n"
      "also the files `classify test --csv` writes. Keywords (the command line's options, with\n"
      "underscores):",
      py::arg("model"), py::arg("recordings"), py::arg("labels"));
  m.def("predict", &predict, py::arg("model"), py::arg("files"),
        "(class, value or None) of each recording (BioTac-style CSV).");
}

}  // namespace tactile::python
