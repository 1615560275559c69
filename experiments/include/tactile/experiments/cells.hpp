#pragma once
// An experiment as independent cells, so that any scheduler (the local thread pool, a shell loop,
// GNU parallel, a Slurm job array) can run them in any order and any number of times:
//   plan     the manifest: one line per cell (stable id, kind, inputs, folder);
//   cell     one cell run into its own folder, skipped when its done marker exists;
//   merge    every cell's rows gathered in manifest order into the files run_experiment writes;
//   status   what each cell's status file says: done, running, failed or missing, and CPU time.
// File formats: docs/formats.md ("Experiment manifest", "Cell folders").

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "tactile/common/names.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::experiments {

// "run": one mapping of the grid (its movie, metrics row and activity); "perception": the whole
// perception section (every mapping's Table 2 and the sensor's).
enum class CellKind { run, perception };
inline constexpr std::array<Named<CellKind>, 2> kCellKindNames = {{
    {CellKind::run, "run"},
    {CellKind::perception, "perception"},
}};
std::string to_string(CellKind kind);

struct Cell {
  std::size_t index = 0;
  std::string id;  // "run-<16 hex>": a hash of everything the cell's outputs depend on
  CellKind kind = CellKind::run;
  std::string name;  // the run's id ("003-bump-stress-integrated-per-frame") or "perception"
  std::vector<std::string> inputs;  // what it reads, as a person names it
  std::filesystem::path folder;     // relative to the output folder: cells/<id>
  std::size_t run = 0;              // index into Experiment::runs (run cells)
};

struct Plan {
  std::string experiment;       // its name
  std::string experiment_hash;  // 16 hex digits of the experiment file's text
  std::vector<Cell> cells;      // the runs in order, then the perception cell if any
};

Plan plan_experiment(const Experiment& experiment);

// <out_dir>/manifest.tsv, and experiment.json (the input as given); out_dir is created.
std::filesystem::path write_manifest(const Experiment& experiment, const Plan& plan,
                                     const std::filesystem::path& out_dir);
// Throws FormatError naming the file and line when the manifest is missing, damaged, or was
// planned from another experiment than `plan` (then: plan again).
void check_manifest(const Plan& plan, const std::filesystem::path& out_dir);

// The cell chosen by `--cell`: its id, or its index written in decimal. Throws
// std::invalid_argument naming the choice and the valid range.
std::size_t find_cell(const Plan& plan, const std::string& id_or_index);

enum class CellState { done, running, failed, missing };
inline constexpr std::array<Named<CellState>, 4> kCellStateNames = {{
    {CellState::done, "done"},
    {CellState::running, "running"},
    {CellState::failed, "failed"},
    {CellState::missing, "missing"},
}};
std::string to_string(CellState state);

struct CellStatus {
  CellState state = CellState::missing;
  double cpu_s = 0;  // CPU seconds of the last attempt (done or failed)
  double wall_s = 0;
  int attempts = 0;     // how many times the cell was started
  std::string runner;   // where it ran: host, pid, Slurm job
  std::string message;  // why it failed
};

// The cell's state from its folder: done when the done marker exists; otherwise its status file
// (running, failed) or missing. A cell whose status says running on this host with a process
// that no longer exists was stopped while running: failed.
CellStatus cell_status(const Cell& cell, const std::filesystem::path& out_dir);

struct CellContext {
  int threads = 0;          // the cell's own workers (0: all cores)
  std::string runner;       // recorded in the status file
  bool own_process = true;  // CPU time: the process's, else the thread's
  // A run's source as prepared and the strain it maps (run_steps), made by the caller; when
  // null the cell makes them itself.
  const capture::StrainMovie* base = nullptr;
  const capture::StrainMovie* strain = nullptr;
  std::mutex* hdf5 = nullptr;  // held while writing HDF5 (in-process runs)
  std::function<void(const std::string&)> progress;
};

struct CellOutcome {
  bool skipped = false;  // its done marker existed
  double cpu_s = 0;
  double wall_s = 0;
  std::vector<PerceptionTable> perception;  // the tables a perception cell computed
};

// Runs one cell into out_dir (movies/<run>.h5, perception/..., cells/<id>/result.json), then
// writes its status and, last, its done marker, each atomically. A cell already done is skipped.
// On failure the status says so, no marker is written, and the exception is passed on.
CellOutcome run_cell(const Experiment& experiment, const Plan& plan, std::size_t index,
                     const std::filesystem::path& out_dir, const CellContext& context);

struct MergeReport {
  std::vector<RunResult> results;  // in the order of Experiment::runs
  std::vector<PerceptionLine> perception;
  std::vector<std::string> incomplete;       // "<id> (<name>): failed|running|missing ..."
  std::vector<std::filesystem::path> files;  // everything written
};

// Gathers every cell's results in manifest order and writes resolved.json, metrics.csv and the
// plots, as run_experiment documents. When any cell is not done, writes nothing and lists them.
MergeReport merge_experiment(const Experiment& experiment, const Plan& plan,
                             const std::filesystem::path& out_dir, int threads);

struct KindStatus {
  CellKind kind = CellKind::run;
  std::size_t cells = 0, done = 0, running = 0, failed = 0, missing = 0;
  double cpu_s = 0;  // of the done cells
  double wall_s = 0;
};
struct ExperimentStatus {
  std::vector<KindStatus> kinds;   // the kinds the plan has, in kCellKindNames order
  std::vector<std::string> notes;  // one per cell not done: id, name, state, runner, message
};
ExperimentStatus experiment_status(const Plan& plan, const std::filesystem::path& out_dir);

}  // namespace tactile::experiments
