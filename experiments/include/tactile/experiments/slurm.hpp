#pragma once
// An experiment's cells on a Slurm cluster: a job array whose tasks run the cells through
// `tactile experiment --cell`, and a merge job that waits for the array (afterok). Only the
// scripts and the sbatch call live here; Slurm schedules. Format: docs/experiments.md.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "tactile/experiments/cells.hpp"

namespace tactile::experiments {

struct SlurmOptions {
  std::string partition;   // empty: the cluster's default
  int max_parallel = 0;    // tasks running at once (--array=...%K); 0: no limit
  int cells_per_task = 1;  // cells one array task runs one after the other
  std::string time_limit;  // per task and for the merge, as sbatch --time takes it; empty: none
};

// Throws std::invalid_argument unless `limit` is one of sbatch's time formats: M, M:S, H:M:S,
// D-H, D-H:M, D-H:M:S (whole numbers).
void check_time_limit(const std::string& limit);

// Throws std::invalid_argument, naming the option, unless `options` and `out_dir` (absolute)
// can be written into the scripts as they are: a number out of range or a bad time limit; a
// partition list whose names are not plain names (a line break would start a command of its
// own); an output folder whose path holds what sbatch reads otherwise in an #SBATCH line
// (white space, quotes, a backslash, '#', '%') or a control character.
void check_slurm_options(const SlurmOptions& options, const std::filesystem::path& out_dir);

// Slurm refuses array indices above MaxArraySize - 1 (1001 by default).
inline constexpr std::size_t kDefaultMaxArraySize = 1001;

struct SlurmJobs {
  std::filesystem::path cells_script;  // empty when no cell is left to run
  std::filesystem::path merge_script;
  std::size_t cells = 0;  // cells the array runs (those not done when written)
  std::size_t tasks = 0;
  // The two sbatch calls; the merge's --dependency needs the array's job id (ARRAY_JOB).
  std::vector<std::string> cells_command, merge_command;
};

// Writes out_dir/slurm/cells.sh and merge.sh (and creates slurm/logs for their output) for the
// cells of `plan` not done yet. `program`, `experiment_file` and `out_dir` must be absolute paths
// the cluster's nodes see. Throws std::invalid_argument, before writing anything, when
// check_slurm_options does or when the array would exceed kDefaultMaxArraySize tasks (naming the
// --cells-per-task that fits).
SlurmJobs write_slurm_jobs(const Plan& plan, const std::filesystem::path& out_dir,
                           const std::filesystem::path& program,
                           const std::filesystem::path& experiment_file,
                           const SlurmOptions& options);

// The commands as a person types them in a shell (the merge's dependency from the array's id).
std::string slurm_commands_text(const SlurmJobs& jobs);

// Runs `command` (sbatch --parsable ...) and returns the job id it prints. Throws
// std::runtime_error with sbatch's own message when it cannot run or fails.
std::string submit_batch(std::vector<std::string> command);

// `command` with "ARRAY_JOB" in its arguments replaced by `array_job`.
std::vector<std::string> with_array_job(std::vector<std::string> command,
                                        const std::string& array_job);

}  // namespace tactile::experiments
