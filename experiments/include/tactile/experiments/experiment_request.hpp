#pragma once
// `experiment` as a request: an experiment file run into a folder, its option table (read by the
// command line and the Python module alike) and resolve(), which reads and checks the whole
// file, decides the output folder and refuses one that would write over the experiment's inputs,
// before any work. The command line's cluster modes (--plan, --cell, --merge, --slurm) are the
// same run cut into cells; they are the command line's own.

#include <filesystem>
#include <optional>
#include <vector>

#include "tactile/common/option_table.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::experiments {

struct ExperimentRequest {
  std::filesystem::path file;                // the experiment (JSON)
  std::optional<std::filesystem::path> out;  // unset: <experiment name>-results
  int threads = 0;                           // 0: all cores
  bool quiet = false;                        // no progress messages
};

const std::vector<OptionRow<ExperimentRequest>>& experiment_options();

struct ResolvedExperiment {
  Experiment experiment;
  std::filesystem::path out;
};

// Every value against its row (RequestError in the front end's spelling), then the file read
// and checked whole (FormatError naming it), the folder decided, and an output over the file,
// a source or a layout file refused (OutputPathError).
ResolvedExperiment resolve(const ExperimentRequest& request, OptionSpelling spelling);

}  // namespace tactile::experiments
