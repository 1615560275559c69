#pragma once
// The steps of running an experiment, shared by the one-machine run (run.cpp) and the cells
// (cells.cpp): a source made ready, one run mapped, and the merged files written.

#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tactile/experiments/experiment.hpp"

namespace tactile::experiments {

// The source's strain movie: read, rendered and measured, or its exact ground truth.
capture::StrainMovie prepare_source(const ExperimentSource& source);

// The strain a run maps: the source's own, or accumulated along its tracks.
capture::StrainMovie run_strain(const capture::StrainMovie& base, const ExperimentSource& source,
                                const mapping::MappingParams& params);

// "tactile <version> experiment '<name>' (<origin>), seed <seed>, <created>".
std::string made_by(const Experiment& experiment, const std::string& created_utc);

nlohmann::json source_json(const ExperimentSource& source);

struct MappedRun {
  RunResult result;
  nlohmann::json resolved;  // its entry in resolved.json's "runs"
  std::string metrics_row;  // its line of metrics.csv, without the newline
};

// Maps run `index` of `base` (the source as prepared) and `strain` (run_strain of it), writes
// its movie into out_dir/movies when the experiment writes movies (holding `hdf5` if given).
MappedRun map_run(const Experiment& experiment, std::size_t index, const capture::StrainMovie& base,
                  const capture::StrainMovie& strain, const std::filesystem::path& out_dir,
                  const std::string& created_utc, std::mutex* hdf5);

// resolved.json, metrics.csv and the plots from every run's results (in run order); appended to
// `files`.
void write_merged(const Experiment& experiment, const std::vector<MappedRun>& runs,
                  const std::filesystem::path& out_dir, const std::string& made_by_text,
                  int threads, std::vector<std::filesystem::path>& files);

// The experiment file as given.
std::filesystem::path write_experiment_copy(const Experiment& experiment,
                                            const std::filesystem::path& out_dir);

}  // namespace tactile::experiments
