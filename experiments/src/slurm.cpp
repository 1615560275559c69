// Slurm job scripts for an experiment's cells, and their submission with sbatch.

#include "tactile/experiments/slurm.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/plain_name.hpp"

extern char** environ;

namespace tactile::experiments {
namespace {

namespace fs = std::filesystem;

// A word the shell takes as is: single-quoted, a quote inside written '\''.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string common_directives(const std::string& job_name, const SlurmOptions& o) {
  std::string d = fmt::format("#SBATCH --job-name={}\n", job_name);
  if (!o.partition.empty()) d += fmt::format("#SBATCH --partition={}\n", o.partition);
  if (!o.time_limit.empty()) d += fmt::format("#SBATCH --time={}\n", o.time_limit);
  return d;
}

// A job name Slurm prints without trouble: the experiment's name, letters, digits, - _ . only.
std::string job_name(const std::string& experiment, const char* suffix) {
  std::string name;
  for (const char c : experiment)
    name +=
        std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
  return name + suffix;
}

}  // namespace

void check_time_limit(const std::string& limit) {
  const auto digits = [](const std::string& part) {
    return !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
  };
  // [D-]A[:B[:C]], all whole numbers; at most one '-'.
  const auto dash = limit.find('-');
  bool ok = dash == std::string::npos ||
            (digits(limit.substr(0, dash)) && limit.find('-', dash + 1) == std::string::npos);
  const std::string clock = dash == std::string::npos ? limit : limit.substr(dash + 1);
  int parts = 0;
  for (std::size_t from = 0; ok; ++parts) {
    const auto colon = clock.find(':', from);
    ok = digits(clock.substr(from, colon - from));
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  if (!ok || parts > 2)
    throw std::invalid_argument(fmt::format(
        "--time {}: not a Slurm time limit (minutes, M:S, H:M:S, D-H, D-H:M or D-H:M:S)", limit));
}

void check_slurm_options(const SlurmOptions& o, const fs::path& out_dir) {
  if (o.cells_per_task < 1 || o.max_parallel < 0)
    throw std::invalid_argument("--cells-per-task must be >= 1 and --max-parallel >= 0");
  if (!o.time_limit.empty()) check_time_limit(o.time_limit);
  // Written unquoted after "#SBATCH --partition=": sbatch takes a comma-separated list.
  for (std::size_t from = 0; !o.partition.empty() && from <= o.partition.size();) {
    const auto comma = std::min(o.partition.find(',', from), o.partition.size());
    if (const auto error = plain_name_error("--partition", o.partition.substr(from, comma - from)))
      throw std::invalid_argument(*error);
    from = comma + 1;
  }
  // The shell lines quote the folder; the #SBATCH lines cannot (sbatch splits them itself, and
  // reads '%' in --output as a pattern), and a line break would end a comment line of the script.
  const std::string folder = out_dir.string();
  for (const char c : folder) {
    const auto u = static_cast<unsigned char>(c);
    const bool bad = u < 0x20 || u == 0x7f || c == ' ' || c == '\'' || c == '"' || c == '\\' ||
                     c == '#' || c == '%';
    if (bad)
      throw std::invalid_argument(fmt::format(
          "--out {:?}: the Slurm scripts name this folder in #SBATCH lines, where sbatch splits "
          "at white space and reads quotes, backslashes, '#' and '%' as its own; it holds {}: "
          "choose a folder whose path has none of these and no control character",
          folder,
          u < 0x20 || u == 0x7f ? std::string("a control character") : fmt::format("'{}'", c)));
  }
}

SlurmJobs write_slurm_jobs(const Plan& plan, const fs::path& out_dir, const fs::path& program,
                           const fs::path& experiment_file, const SlurmOptions& o) {
  check_slurm_options(o, out_dir);
  std::vector<std::size_t> pending;
  for (const auto& cell : plan.cells)
    if (cell_status(cell, out_dir).state != CellState::done) pending.push_back(cell.index);
  SlurmJobs jobs;
  jobs.cells = pending.size();
  const auto per_task = static_cast<std::size_t>(o.cells_per_task);
  jobs.tasks = (pending.size() + per_task - 1) / per_task;
  if (jobs.tasks > kDefaultMaxArraySize) {
    throw std::invalid_argument(fmt::format(
        "{} cells at --cells-per-task {} make {} array tasks; Slurm allows {} by default "
        "(MaxArraySize): use --cells-per-task {} or more",
        pending.size(), o.cells_per_task, jobs.tasks, kDefaultMaxArraySize,
        (pending.size() + kDefaultMaxArraySize - 1) / kDefaultMaxArraySize));
  }
  const fs::path dir = out_dir / "slurm";
  fs::create_directories(dir / "logs");
  const std::string run_cell =
      fmt::format("{} experiment {} --out {}", quoted(program.string()),
                  quoted(experiment_file.string()), quoted(out_dir.string()));
  if (jobs.tasks > 0) {
    std::string list;
    for (std::size_t i = 0; i < pending.size(); ++i)
      list += (i % 20 == 0 ? "\n  " : " ") + std::to_string(pending[i]);
    std::string script = "#!/bin/bash\n";
    script += common_directives(job_name(plan.experiment, "-cells"), o);
    script += fmt::format("#SBATCH --array=0-{}{}\n", jobs.tasks - 1,
                          o.max_parallel > 0 ? fmt::format("%{}", o.max_parallel) : "");
    script += fmt::format("#SBATCH --output={}\n", (dir / "logs" / "cells-%A_%a.log").string());
    // A cell's threads follow the task's CPUs, which `sbatch --cpus-per-task=C` raises.
    script += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
    script += fmt::format(
        "# Cells of {} not done when this was written; task T runs cells[T*{} .. T*{}+{}].\n"
        "# A cell already done is skipped, so a task run twice does no work twice.\n"
        "cells=({}\n)\n"
        "per_task={}\n"
        "first=$((SLURM_ARRAY_TASK_ID * per_task))\n"
        "args=()\n"
        "for ((i = first; i < first + per_task && i < ${{#cells[@]}}; ++i)); do\n"
        "  args+=(--cell \"${{cells[i]}}\")\n"
        "done\n"
        "# One process for the task's cells: it runs each even when one fails, then exits 1.\n"
        "exec {} \"${{args[@]}}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" --quiet\n",
        (out_dir / "manifest.tsv").string(), per_task, per_task, per_task - 1, list, per_task,
        run_cell);
    jobs.cells_script = dir / "cells.sh";
    write_text_atomically(jobs.cells_script, script);
    jobs.cells_command = {"sbatch", "--parsable", jobs.cells_script.string()};
  }
  std::string merge = "#!/bin/bash\n";
  merge += common_directives(job_name(plan.experiment, "-merge"), o);
  merge += fmt::format("#SBATCH --output={}\n", (dir / "logs" / "merge-%j.log").string());
  merge += "#SBATCH --ntasks=1\n";
  merge += fmt::format("exec {} --merge\n", run_cell);
  jobs.merge_script = dir / "merge.sh";
  write_text_atomically(jobs.merge_script, merge);
  jobs.merge_command = {"sbatch", "--parsable"};
  if (jobs.tasks > 0) jobs.merge_command.push_back("--dependency=afterok:ARRAY_JOB");
  jobs.merge_command.push_back(jobs.merge_script.string());
  return jobs;
}

std::string slurm_commands_text(const SlurmJobs& jobs) {
  const auto line = [](const std::vector<std::string>& command) {
    std::string s;
    for (const auto& word : command) {
      if (!s.empty()) s += ' ';
      s += word.find_first_not_of(
               "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_"
               "./=:") == std::string::npos
               ? word
               : quoted(word);
    }
    return s;
  };
  if (jobs.tasks == 0) return line(jobs.merge_command) + "\n";
  // The array's id goes in unquoted by line() and is then replaced by a shell expansion.
  std::string merge = line(jobs.merge_command);
  merge.replace(merge.find("ARRAY_JOB"), 9, "\"${array_job%%;*}\"");
  return fmt::format("array_job=$({})\n{}\n", line(jobs.cells_command), merge);
}

std::vector<std::string> with_array_job(std::vector<std::string> command,
                                        const std::string& array_job) {
  for (auto& word : command) {
    const auto at = word.find("ARRAY_JOB");
    if (at != std::string::npos) word.replace(at, 9, array_job);
  }
  return command;
}

std::string submit_batch(std::vector<std::string> command) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error(fmt::format("pipe: {}", std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, out[1], 2);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  posix_spawn_file_actions_addclose(&actions, out[1]);
  std::vector<char*> argv;
  for (auto& word : command) argv.push_back(word.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (spawned != 0) {
    close(out[0]);
    throw std::runtime_error(
        fmt::format("cannot run {}: {} (is Slurm's client installed and on PATH?)", command[0],
                    std::strerror(spawned)));
  }
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(out[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  close(out[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::string whole;
  for (const auto& word : command) whole += (whole.empty() ? "" : " ") + word;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("{} failed: {}", whole, text));
  // --parsable prints "<job id>" or "<job id>;<cluster>".
  const std::string id = text.substr(0, text.find(';'));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error(fmt::format("{}: expected a job id, got '{}'", whole, text));
  return id;
}

}  // namespace tactile::experiments
