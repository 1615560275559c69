// experiment(file, ...): an experiment file run into its folder, as `tactile experiment` runs it
// without its cluster modes (experiments::run_experiment), its keywords made from the
// experiment request's option table; returns each run's figures and the files written.

#include <string>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/experiments/experiment_request.hpp"

namespace tactile::python {

namespace {

py::dict run(const std::filesystem::path& file, const py::kwargs& kwargs) {
  experiments::ExperimentRequest request;
  request.file = file;
  set_from_kwargs(request, experiments::experiment_options(), kwargs, "experiment");
  experiments::ExperimentReport report;
  std::vector<std::string> run_ids;
  std::filesystem::path out;
  {
    py::gil_scoped_release unlocked;
    experiments::ResolvedExperiment resolved =
        with_inputs({file}, [&] { return experiments::resolve(request, OptionSpelling::python); });
    out = resolved.out;
    for (const auto& r : resolved.experiment.runs) run_ids.push_back(r.id);
    report = experiments::run_experiment(std::move(resolved.experiment), out, request.threads,
                                         [quiet = request.quiet](const std::string& message) {
                                           if (!quiet) write_python_stdout("  " + message + "\n");
                                         });
  }
  py::list runs;
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const auto& r = report.results[i];
    py::dict d;
    d["id"] = run_ids.at(i);
    d["frames"] = r.frames;
    d["strain_correlation"] = r.metrics.strain_correlation;
    d["strain_rms_error"] = r.metrics.strain_rms_error;
    d["saturated_fraction"] = r.metrics.saturated_fraction;
    d["map_ms"] = r.map_ms;
    runs.append(d);
  }
  py::dict out_dict;
  out_dict["out"] = out;
  out_dict["runs"] = runs;
  out_dict["files"] = report.files;
  out_dict["threads"] = report.threads;
  return out_dict;
}

}  // namespace

void bind_experiment(py::module_& m) {
  def_with_kwargs(
      m, "experiment", &run, experiments::experiment_options(),
      "Runs an experiment file (every source x layout x method x parameter combination, in\n"
      "parallel) into its folder, as `tactile experiment` does without its cluster modes:\n"
      "movies, metrics.csv, plots, resolved.json. Returns out, runs (id, frames,\n"
      "strain_correlation, strain_rms_error, saturated_fraction, map_ms), files and threads.\n"
      "Keywords (the command line's options, with underscores):",
      py::arg("file"));
}

}  // namespace tactile::python
