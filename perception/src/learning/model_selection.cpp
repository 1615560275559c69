// Options chosen by cross-validation, scored by nested cross-validation (see model_selection.hpp).

#include "tactile/perception/model_selection.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/common/names.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/perception/svm_model.hpp"

namespace tactile::perception {
namespace {

// One analysis of every recording per (baseline, electrodes, trim), each group's inputs apart,
// so that every set of groups is a concatenation and the costly analysis runs once per setting.
struct AnalysedGrid {
  std::vector<InputGroup> groups;               // the union of the grid's input sets
  std::vector<RecordingInputOptions> settings;  // groups = the union
  std::vector<std::vector<std::vector<std::vector<double>>>> inputs;  // [setting][row][group]
};

AnalysedGrid analyse_grid(const LabelledRecordings& data, const RecordingInputOptions& base,
                          const SelectionGrid& grid, int threads) {
  AnalysedGrid a;
  for (const auto& set : grid.input_sets)
    for (const auto g : set)
      if (std::find(a.groups.begin(), a.groups.end(), g) == a.groups.end()) a.groups.push_back(g);
  for (const auto b : grid.baselines)
    for (const auto e : grid.electrodes)
      for (const double t : grid.trims) {
        auto o = base;
        o.groups = a.groups;
        o.contact.baseline_at = b;
        o.contact.electrodes = e;
        o.contact.trim_fraction = t;
        a.settings.push_back(o);
      }
  const std::size_t n = data.recordings.size();
  a.inputs.assign(a.settings.size(), std::vector<std::vector<std::vector<double>>>(n));
  parallel_for(a.settings.size() * n, worker_count(threads), [&](std::size_t job) {
    const std::size_t s = job / n, i = job % n;
    a.inputs[s][i] = recording_inputs_by_group(data.recordings[i], a.settings[s]);
  });
  return a;
}

// The labelled inputs of one setting and set of groups, in the model's fixed group order.
LabelledInputs candidate_inputs(const LabelledRecordings& data, const AnalysedGrid& a,
                                std::size_t setting, const std::vector<InputGroup>& set) {
  LabelledInputs d;
  d.options = a.settings[setting];
  d.options.groups = set;
  d.options.groups = selected_groups(d.options);
  d.input_names = recording_input_names(d.options);
  d.class_names = data.class_names;
  d.files = data.files;
  d.classes = data.classes;
  d.values = data.values;
  for (const auto& by_group : a.inputs[setting]) {
    auto& row = d.rows.emplace_back();
    for (const auto g : d.options.groups) {
      const auto& v = by_group[static_cast<std::size_t>(
          std::find(a.groups.begin(), a.groups.end(), g) - a.groups.begin())];
      row.insert(row.end(), v.begin(), v.end());
    }
  }
  return d;
}

struct CandidateData {
  SelectionCandidate candidate;
  std::size_t inputs = 0;  // index into the per-(setting, set) inputs
  std::size_t input_count = 0;
};

// Whether candidate a is preferred to b at equal score: the simpler one.
bool simpler(const CandidateData& a, const CandidateData& b) {
  const auto key = [](const CandidateData& c) {
    return std::make_tuple(c.input_count, c.candidate.svm.degree,
                           std::abs(std::log(c.candidate.svm.c)));
  };
  return key(a) < key(b);
}

struct Selections {
  std::vector<LabelledInputs> inputs;  // per (setting, input set)
  std::vector<CandidateData> candidates;
  std::vector<SelectionRecord> records;  // per split
};

// Scores every candidate on every split (rows of the training set) by cross-validation.
Selections run_selections(const LabelledRecordings& data, const RecordingInputOptions& base,
                          const SelectionGrid& grid,
                          const std::vector<std::vector<std::size_t>>& splits, int folds,
                          int threads) {
  if (grid.size() == 0) throw std::invalid_argument("model selection: the grid is empty");
  std::vector<int> split_folds;
  for (const auto& rows : splits) {
    std::vector<int> classes;
    for (const auto i : rows) classes.push_back(data.classes.at(i));
    const int smallest = class_sizes(classes).first;
    if (smallest < 2)
      throw std::invalid_argument(fmt::format(
          "choosing options needs at least 2 recordings of every class in the training set "
          "(a class has {})",
          smallest));
    split_folds.push_back(std::min(folds, smallest));
  }
  const auto analysed = analyse_grid(data, base, grid, threads);
  Selections s;
  for (std::size_t setting = 0; setting < analysed.settings.size(); ++setting)
    for (const auto& set : grid.input_sets) {
      s.inputs.push_back(candidate_inputs(data, analysed, setting, set));
      for (const int degree : grid.degrees)
        for (const double c : grid.cs) {
          CandidateData cd;
          cd.candidate.inputs = s.inputs.back().options;
          cd.candidate.svm.degree = degree;
          cd.candidate.svm.c = c;
          cd.inputs = s.inputs.size() - 1;
          cd.input_count = s.inputs.back().input_names.size();
          s.candidates.push_back(cd);
        }
    }
  // One job per (split, inputs, fold): the candidates on the same inputs differ only in exponent
  // and C and share the fold's kernel matrix. Folds as cross_validate makes them on the split's
  // rows, so each candidate's count is its cross-validation's.
  const std::size_t n = s.candidates.size();
  std::vector<std::vector<std::size_t>> by_inputs(s.inputs.size());
  for (std::size_t k = 0; k < n; ++k) by_inputs[s.candidates[k].inputs].push_back(k);
  std::vector<std::vector<int>> fold_of;
  for (std::size_t split = 0; split < splits.size(); ++split) {
    std::vector<int> classes;
    for (const auto i : splits[split]) classes.push_back(data.classes[i]);
    fold_of.push_back(stratified_folds(classes, split_folds[split]));
  }
  std::vector<std::size_t> job_split, job_fold;
  for (std::size_t split = 0; split < splits.size(); ++split)
    for (int k = 0; k < split_folds[split]; ++k) {
      job_split.push_back(split);
      job_fold.push_back(static_cast<std::size_t>(k));
    }
  // [job x inputs][candidate of those inputs]: rows correct on the job's test fold.
  std::vector<std::vector<int>> correct(job_split.size() * s.inputs.size());
  std::vector<int> tested(job_split.size(), 0);
  parallel_for(correct.size(), worker_count(threads), [&](std::size_t job) {
    const std::size_t j = job / s.inputs.size(), in = job % s.inputs.size();
    const auto& rows = splits[job_split[j]];
    const auto& folds = fold_of[job_split[j]];
    const auto& d = s.inputs[in];
    SvmRows train, test;
    std::vector<int> train_classes, test_classes;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const bool held_out = folds[i] == static_cast<int>(job_fold[j]);
      (held_out ? test : train).push_back(d.rows[rows[i]]);
      (held_out ? test_classes : train_classes).push_back(d.classes[rows[i]]);
    }
    std::vector<SvmOptions> options;
    for (const auto k : by_inputs[in]) options.push_back(s.candidates[k].candidate.svm);
    const auto predicted = classify_with_each(train, train_classes, test, options);
    auto& count = correct[job];
    for (const auto& classes : predicted) {
      int right = 0;
      for (std::size_t i = 0; i < classes.size(); ++i) right += classes[i] == test_classes[i];
      count.push_back(right);
    }
    if (in == 0) tested[j] = static_cast<int>(test.size());
  });
  std::vector<int> split_correct(splits.size() * n, 0), split_tested(splits.size(), 0);
  for (std::size_t j = 0; j < job_split.size(); ++j) {
    split_tested[job_split[j]] += tested[j];
    for (std::size_t in = 0; in < s.inputs.size(); ++in)
      for (std::size_t m = 0; m < by_inputs[in].size(); ++m)
        split_correct[job_split[j] * n + by_inputs[in][m]] += correct[j * s.inputs.size() + in][m];
  }
  for (std::size_t split = 0; split < splits.size(); ++split) {
    SelectionRecord r;
    r.folds = split_folds[split];
    for (std::size_t k = 0; k < n; ++k) {
      auto c = s.candidates[k].candidate;
      c.correct = split_correct[split * n + k];
      c.tested = split_tested[split];
      r.candidates.push_back(c);
      const auto& best = r.candidates[r.chosen];
      if (c.correct > best.correct ||
          (c.correct == best.correct && simpler(s.candidates[k], s.candidates[r.chosen])))
        r.chosen = k;
    }
    s.records.push_back(std::move(r));
  }
  return s;
}

std::vector<std::size_t> all_rows(std::size_t n) {
  std::vector<std::size_t> rows(n);
  for (std::size_t i = 0; i < n; ++i) rows[i] = i;
  return rows;
}

}  // namespace

SelectionGrid default_selection_grid(RecordingProcedure procedure) {
  auto o = default_recording_inputs(procedure);
  SelectionGrid g;
  using G = InputGroup;
  if (o.procedure == Procedure::static_contact) {
    g.input_sets = {{G::stats}, {G::means}, {G::means, G::stats}};
    g.trims = {0.0};
  } else {
    g.input_sets = {{G::stats},
                    {G::means, G::bands},
                    {G::means, G::rates, G::hht},
                    {G::means, G::stats},
                    {G::means, G::rates, G::hht, G::stats}};
    g.trims = {0.0, 0.1, 0.2};
  }
  g.baselines = {ContactOptions::BaselineAt::none, ContactOptions::BaselineAt::end};
  g.electrodes = {ContactOptions::Electrodes::each, ContactOptions::Electrodes::clusters};
  g.degrees = {1, 2};
  g.cs = {0.01, 0.1, 1.0, 10.0, 100.0, 1000.0};
  return g;
}

SelectionRecord select_options(const LabelledRecordings& data, const RecordingInputOptions& base,
                               const SelectionGrid& grid, int folds,
                               const std::vector<std::size_t>& rows, int threads) {
  const auto split = rows.empty() ? all_rows(data.recordings.size()) : rows;
  return run_selections(data, base, grid, {split}, folds, threads).records.front();
}

ClassifierModel make_selected_model(const LabelledRecordings& data, const SelectionRecord& record,
                                    int threads) {
  const auto& chosen = record.candidates.at(record.chosen);
  auto model = make_classifier_model(analyse_recordings(data, chosen.inputs, threads), chosen.svm);
  model.selection = record;
  return model;
}

NestedCrossValidation nested_cross_validate(const LabelledRecordings& data,
                                            const RecordingInputOptions& base,
                                            const SelectionGrid& grid, int outer_folds,
                                            int inner_folds, int threads) {
  check_fold_count(data.classes, outer_folds);
  const auto fold_of = stratified_folds(data.classes, outer_folds);
  std::vector<std::vector<std::size_t>> train(static_cast<std::size_t>(outer_folds)),
      test(static_cast<std::size_t>(outer_folds));
  for (std::size_t i = 0; i < fold_of.size(); ++i)
    for (std::size_t k = 0; k < train.size(); ++k)
      (fold_of[i] == static_cast<int>(k) ? test[k] : train[k]).push_back(i);
  auto splits = train;
  splits.push_back(all_rows(data.recordings.size()));
  const auto s = run_selections(data, base, grid, splits, inner_folds, threads);
  NestedCrossValidation nested;
  std::vector<ClassifierTest> results(train.size());
  parallel_for(train.size(), worker_count(threads), [&](std::size_t k) {
    const auto& record = s.records[k];
    const auto& inputs = s.inputs[s.candidates[record.chosen].inputs];
    const Classifier c(
        make_classifier_model(subset(inputs, train[k]), record.candidates[record.chosen].svm));
    results[k] = test_classifier(c, data.class_names.size(), subset(inputs, test[k]));
  });
  nested.outer = pool_folds(results);
  for (std::size_t k = 0; k < results.size(); ++k)
    nested.chosen.push_back(s.records[k].candidates[s.records[k].chosen]);
  nested.overall = s.records.back();
  return nested;
}

SelectionGrid selection_grid_for(const ClassifierTraining& t) {
  auto grid = default_selection_grid(t.procedure);
  if (t.baseline_at) grid.baselines = {*t.baseline_at};
  if (t.electrodes) grid.electrodes = {*t.electrodes};
  if (t.trim) {
    check_trim_fraction(*t.trim);
    grid.trims = {*t.trim};
  }
  if (!t.inputs.empty()) grid.input_sets = {t.inputs};
  if (t.kernel_degree) grid.degrees = {*t.kernel_degree};
  if (t.c) grid.cs = {*t.c};
  return grid;
}

ClassifierTrainingRun train_classifier(const std::filesystem::path& recordings,
                                       const std::filesystem::path& labels,
                                       const ClassifierTraining& training, int threads) {
  ClassifierTrainingRun run;
  if (training.select) {
    const auto base = default_recording_inputs(training.procedure);
    const auto grid = selection_grid_for(training);
    run.candidates = grid.size();
    const auto data = read_labelled_recordings(recordings, labels, {}, threads);
    require_two_classes(data.class_names, labels);
    SelectionRecord record;
    if (training.cv_folds > 0) {
      run.nested =
          nested_cross_validate(data, base, grid, training.cv_folds, kSelectionFolds, threads);
      record = run.nested->overall;
    } else {
      record = select_options(data, base, grid, kSelectionFolds, {}, threads);
    }
    run.model = make_selected_model(data, record, threads);
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    const auto in = recording_inputs_for(training);
    const auto svm = svm_options_for(training);
    const auto data = load_labelled_recordings(recordings, labels, in, {}, threads);
    run.analysis_s = seconds_since(t0);
    require_two_classes(data.class_names, labels);
    if (training.cv_folds > 0) run.cv = cross_validate(data, svm, training.cv_folds, threads);
    run.model = make_classifier_model(data, svm);
  }
  const auto& m = run.model;
  const Classifier fitted(m);  // checks that it trains before anything is written
  run.training_fit = test_classifier(fitted, m.class_names.size(),
                                     LabelledInputs{.options = m.options,
                                                    .input_names = m.input_names,
                                                    .class_names = m.class_names,
                                                    .files = m.files,
                                                    .rows = m.rows,
                                                    .classes = m.classes,
                                                    .values = m.values});
  return run;
}

std::string describe_candidate(const SelectionCandidate& c) {
  return fmt::format("{}; baseline {}, electrodes {}, trim {:g}; exponent {}, C = {:g}",
                     fmt::join(names_of(c.inputs.groups), ","),
                     to_string(c.inputs.contact.baseline_at),
                     to_string(c.inputs.contact.electrodes), c.inputs.contact.trim_fraction,
                     c.svm.degree, c.svm.c);
}

}  // namespace tactile::perception
