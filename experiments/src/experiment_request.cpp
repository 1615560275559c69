// The experiment request's option table and its rules; see experiment_request.hpp.

#include "tactile/experiments/experiment_request.hpp"

#include <fmt/format.h>

#include "tactile/common/output_paths.hpp"

namespace tactile::experiments {

namespace rows = option_rows;

const std::vector<OptionRow<ExperimentRequest>>& experiment_options() {
  using R = ExperimentRequest;
  static const std::vector<OptionRow<R>> table = {
      rows::positional_path<R>("file", &R::file, "EXP_JSON", "Experiment file (JSON)"),
      rows::path<R>("out", &R::out, "Output folder (default: <experiment name>-results)"),
      rows::number<R>("threads", &R::threads, 0, 256, "", "Worker threads (0: all cores)"),
      rows::flag<R>("quiet", &R::quiet, "Print only the summary"),
  };
  return table;
}

ResolvedExperiment resolve(const ExperimentRequest& request, OptionSpelling spelling) {
  check_options(request, experiment_options(), spelling);
  ResolvedExperiment r{read_experiment(request.file), {}};
  const Experiment& ex = r.experiment;
  r.out = request.out.value_or(std::filesystem::path(ex.name + "-results"));
  std::vector<NamedPath> inputs = {
      {spelling == OptionSpelling::cli ? "EXP_JSON" : "file", request.file}};
  for (const auto& s : ex.sources)
    if (!s.path.empty()) inputs.push_back({"source '" + s.name + "'", s.path});
  for (const auto& layout : ex.layout_files) inputs.push_back({"layout", layout});
  refuse_output_over_input({experiment_output(option_label("out", spelling), r.out)}, inputs);
  return r;
}

}  // namespace tactile::experiments
