// The classify requests' option tables and rules; see classify_request.hpp.

#include "tactile/perception/classify_request.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <system_error>

#include "tactile/perception/contact_inputs.hpp"
#include "tactile/perception/recording_inputs.hpp"

namespace tactile::perception {

namespace {

namespace rows = option_rows;

// A named option that must be given: the command line's --recordings DIR, Python's positional.
template <typename R>
OptionRow<R> required(OptionRow<R> row, bool folder) {
  row.required = true;
  row.must_exist = true;
  row.folder = folder;
  return row;
}

template <typename R>
OptionRow<R> threads_row() {
  return rows::number<R>("threads", &R::threads, 0, 256, "", "Worker threads (0: all cores)");
}

}  // namespace

const std::vector<OptionRow<TrainRequest>>& train_options() {
  using R = TrainRequest;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t = {
        required(rows::path<R>("recordings", &R::recordings, "Folder of the recordings"), true),
        required(rows::path<R>("labels", &R::labels, "Labels CSV: file,class[,value]"), false),
        rows::path<R>("out", &R::out, "Model file to write (JSON)"),
        rows::choice<R>(
            "procedure", [](auto& r) -> auto& { return r.training.procedure; },
            kRecordingProcedureNames,
            "What a recording is: stroke (a slide over a texture), static (a press), "
            "or a scene of the paper: dp, ru, roll (feature contact from its "
            "kinematics)"),
        rows::choice<R>(
            "baseline_at", [](auto& r) -> auto& { return r.training.baseline_at; },
            kBaselineAtNames,
            "Where the free-air baseline is: end (recordings that begin in contact), "
            "start, or none (the recording software already subtracted one); "
            "default: none for stroke, end otherwise"),
        rows::choice<R>(
            "electrodes", [](auto& r) -> auto& { return r.training.electrodes; }, kElectrodesNames,
            "Electrode signals of the inputs: clusters (the paper's 6 cluster means) "
            "or each (all 19 electrodes); default: clusters"),
        rows::number<R>(
            "trim", [](auto& r) -> auto& { return r.training.trim; }, 0, 0.5, "",
            "Strokes: fraction of the contact left out at each end, in [0, 0.5) (the "
            "press and the lift of a slide); default: 0.2 for stroke, 0 otherwise"),
        rows::choice_list<R>(
            "inputs", [](auto& r) -> auto& { return r.training.inputs; }, kInputGroupNames,
            "Input groups, comma-separated: means, rates, hht (the paper's), bands (octave band "
            "powers of the vibration), stds (standard deviation of each signal over the contact), "
            "stats (plain statistics: mean and standard deviation of each signal, the "
            "vibration's, and the bands); default: stroke means,bands; dp, ru, roll the paper's "
            "means,rates,hht; static means"),
        rows::number<R>(
            "kernel_degree", [](auto& r) -> auto& { return r.training.kernel_degree; }, 1, 2, "",
            "Exponent of the polynomial kernel; default 1 (searched with --select)"),
        rows::number<R>(
            "c", [](auto& r) -> auto& { return r.training.c; }, 0.001, 100000, "",
            "SVM complexity constant C; default: 100 for stroke, 1 otherwise "
            "(searched with --select)"),
        rows::flag<R>(
            "select", [](auto& r) -> auto& { return r.training.select; },
            "Choose every option not given (inputs, baseline, electrodes, trim, kernel "
            "exponent, C) by 5-fold cross-validation on these recordings; the model "
            "records the comparison"),
        rows::number<R>("cv", &R::cv, 2, 1000, "folds",
                        "Also report stratified K-fold cross-validation accuracy: of the options "
                        "as given (the stroke defaults were chosen on the project's recordings: on "
                        "those, use --select), or with --select nested, the choice made again "
                        "inside each fold"),
        threads_row<R>(),
    };
    for (auto& row : t) {
      // Two kernels, not a range of them.
      if (row.name == "kernel_degree") {
        row.check_number = [](double v) {
          return v == 1 || v == 2 ? std::string() : fmt::format("{} is not 1 or 2", v);
        };
      }
      // The trim's rule is the contact analysis's own (0 included, 0.5 not).
      if (row.name != "trim") continue;
      row.check_number = [](double v) {
        try {
          check_trim_fraction(v);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      };
    }
    return t;
  }();
  return table;
}

ClassifierTraining resolve(const TrainRequest& request, OptionSpelling spelling) {
  check_named_options(request, train_options(), spelling);
  ClassifierTraining t = request.training;
  t.cv_folds = request.cv.value_or(0);
  try {
    recording_inputs_for(t);
    svm_options_for(t);
  } catch (const std::invalid_argument& e) {
    throw RequestError(e.what());
  }
  return t;
}

const std::vector<OptionRow<TestRequest>>& test_options() {
  using R = TestRequest;
  static const std::vector<OptionRow<R>> table = {
      required(rows::path<R>("model", &R::model, "Model file from `classify train`"), false),
      required(rows::path<R>("recordings", &R::recordings, "Folder of the recordings"), true),
      required(rows::path<R>("labels", &R::labels, "Labels CSV: file,class[,value]"), false),
      rows::path<R>("csv", &R::csv,
                    "Folder for confusion.csv, confusion.svg, confusion.png and predictions.csv "
                    "(created if missing)"),
      threads_row<R>(),
  };
  return table;
}

void check_request(const TestRequest& request, OptionSpelling spelling) {
  check_named_options(request, test_options(), spelling);
}

std::vector<NamedPath> classify_inputs(const std::filesystem::path& recordings,
                                       const std::filesystem::path& labels,
                                       const std::filesystem::path& model,
                                       OptionSpelling spelling) {
  std::vector<NamedPath> inputs = {{option_label("labels", spelling), labels}};
  if (!model.empty()) inputs.push_back({option_label("model", spelling), model});
  std::error_code ec;
  const auto options = std::filesystem::directory_options::skip_permission_denied;
  for (auto it = std::filesystem::recursive_directory_iterator(recordings, options, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_directory(ec)) inputs.push_back({option_label("recordings", spelling), it->path()});
  }
  return inputs;
}

}  // namespace tactile::perception
