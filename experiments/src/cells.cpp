// An experiment as independent cells: the manifest, one cell's run with its status file and done
// marker, the merge of every cell's results, and the state of a run in progress.

#include "tactile/experiments/cells.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "run_steps.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/layout_json.hpp"

namespace tactile::experiments {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kManifestMagic = "# tactile experiment manifest, format 1";
constexpr const char* kManifestColumns = "index\tid\tkind\tname\tinputs\tfolder";

// FNV-1a, 64 bits: stable across machines and builds, unlike std::hash.
std::string hash_hex(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return fmt::format("{:016x}", h);
}

std::string source_input(const ExperimentSource& s) {
  if (s.kind == SourceKind::file)
    return fmt::format("source {}: {}", s.name, fs::weakly_canonical(s.path).string());
  return fmt::format("source {}: {} {} scene, seed {}", s.name, to_string(s.kind),
                     to_string(s.scene.scene), s.scene.seed);
}

std::string manifest_line(const Cell& c) {
  std::string inputs;
  for (const auto& i : c.inputs) inputs += (inputs.empty() ? "" : "; ") + i;
  return fmt::format("{}\t{}\t{}\t{}\t{}\t{}", c.index, c.id, to_string(c.kind), c.name, inputs,
                     c.folder.string());
}

std::string manifest_head(const Plan& plan) {
  return fmt::format("{}\n# experiment_hash={} cells={} name={}\n{}\n", kManifestMagic,
                     plan.experiment_hash, plan.cells.size(), plan.experiment, kManifestColumns);
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// JSON has no NaN: written as null, read back as NaN.
double number_or_nan(const json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) throw FormatError(fmt::format("{}: field '{}' is missing", where, key));
  if (j[key].is_null()) return std::numeric_limits<double>::quiet_NaN();
  return json_field<double>(j, key, where);
}

json metrics_json(const mapping::FidelityMetrics& m) {
  return {{"compared_pairs", m.compared_pairs},
          {"strain_rms_error", m.strain_rms_error},
          {"source_strain_rms", m.source_strain_rms},
          {"strain_correlation", m.strain_correlation},
          {"saturated_fraction", m.saturated_fraction},
          {"rms_acceleration_um_per_s2", m.rms_acceleration_um_per_s2},
          {"slew_limited_fraction", m.slew_limited_fraction},
          {"rms_deflection_um", m.rms_deflection_um}};
}

mapping::FidelityMetrics metrics_from(const json& j, const std::string& where) {
  mapping::FidelityMetrics m;
  m.compared_pairs = json_field<std::int64_t>(j, "compared_pairs", where);
  m.strain_rms_error = number_or_nan(j, "strain_rms_error", where);
  m.source_strain_rms = number_or_nan(j, "source_strain_rms", where);
  m.strain_correlation = number_or_nan(j, "strain_correlation", where);
  m.saturated_fraction = number_or_nan(j, "saturated_fraction", where);
  m.rms_acceleration_um_per_s2 = number_or_nan(j, "rms_acceleration_um_per_s2", where);
  m.slew_limited_fraction = number_or_nan(j, "slew_limited_fraction", where);
  m.rms_deflection_um = number_or_nan(j, "rms_deflection_um", where);
  return m;
}

fs::path cell_dir(const Cell& c, const fs::path& out_dir) {
  return out_dir / c.folder;
}

std::optional<json> read_status_json(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / "status.json", ec)) return std::nullopt;
  try {
    return read_json_object(dir / "status.json", "cell status");
  } catch (const FormatError&) {
    return std::nullopt;  // a status being replaced right now, or damaged: as if none
  }
}

void write_status(const fs::path& dir, const json& status) {
  write_text_atomically(dir / "status.json", status.dump(2) + "\n");
}

}  // namespace

std::string to_string(CellKind kind) {
  return name_in(kCellKindNames, kind);
}

std::string to_string(CellState state) {
  return name_in(kCellStateNames, state);
}

Plan plan_experiment(const Experiment& ex) {
  Plan plan;
  plan.experiment = ex.name;
  plan.experiment_hash = hash_hex(ex.text);
  for (std::size_t r = 0; r < ex.runs.size(); ++r) {
    const auto& run = ex.runs[r];
    const auto& source = ex.sources[run.source];
    const auto& layout = ex.layouts[run.layout];
    // Everything the cell's results depend on: its name (in file names), the source, the
    // layout, the parameters, and whether it writes its movie. Not how the experiment file or a
    // source file was named (relative or absolute): a cluster's task names them absolutely.
    json source_key = source_json(source);
    if (source.kind == SourceKind::file) source_key["file"] = fs::weakly_canonical(source.path);
    const std::string key = fmt::format(
        "run\n{}\n{}\n{}\n{}\n{}\n{}", ex.name, run.id, source_key.dump(),
        movie::layout_to_json(layout),
        mapping::parameters_json(run.params, run.params.placement.value_or(mapping::Placement{})),
        ex.write_movies);
    Cell cell;
    cell.index = plan.cells.size();
    cell.kind = CellKind::run;
    cell.id = "run-" + hash_hex(key);
    cell.name = run.id;
    cell.run = r;
    cell.inputs = {source_input(source), "layout " + layout.name};
    cell.folder = fs::path("cells") / cell.id;
    plan.cells.push_back(std::move(cell));
  }
  if (ex.perception) {
    Cell cell;
    cell.index = plan.cells.size();
    cell.kind = CellKind::perception;
    cell.id = "perception-" + hash_hex("perception\n" + ex.text);
    cell.name = "perception";
    cell.inputs = {fmt::format("simulated fingertip, {} trials per feature and procedure",
                               ex.perception->trials)};
    cell.folder = fs::path("cells") / cell.id;
    plan.cells.push_back(std::move(cell));
  }
  for (const auto& c : plan.cells)
    for (const auto& i : c.inputs)
      if (i.find_first_of("\t\n\r") != std::string::npos)
        throw FormatError(fmt::format("{}: input of cell {} holds a tab or line break: '{}'",
                                      ex.origin, c.name, i));
  return plan;
}

fs::path write_manifest(const Experiment& ex, const Plan& plan, const fs::path& out_dir) {
  fs::create_directories(out_dir);
  std::string text = manifest_head(plan);
  for (const auto& c : plan.cells) text += manifest_line(c) + "\n";
  const fs::path path = out_dir / "manifest.tsv";
  write_text_atomically(path, text);
  write_experiment_copy(ex, out_dir);
  return path;
}

void check_manifest(const Plan& plan, const fs::path& out_dir) {
  const fs::path path = out_dir / "manifest.tsv";
  std::ifstream in(path);
  if (!in) {
    throw FormatError(
        fmt::format("{}: no manifest (plan the cells first: tactile experiment "
                    "EXP.json --plan --out {})",
                    path.string(), out_dir.string()));
  }
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw FormatError(fmt::format("{} line {}: {}", path.string(), line, what));
  };
  if (lines.empty() || lines[0] != kManifestMagic)
    fail(1, fmt::format("not an experiment manifest (expected '{}')", kManifestMagic));
  std::string hash, count;
  if (lines.size() < 3) fail(lines.size() + 1, "the manifest ends before its column names");
  {
    std::istringstream head(lines[1]);
    std::string hash_field, cells_field, hash_mark;
    head >> hash_mark >> hash_field >> cells_field;
    if (hash_mark != "#" || !hash_field.starts_with("experiment_hash=") ||
        !cells_field.starts_with("cells="))
      fail(2, "expected '# experiment_hash=<16 hex digits> cells=<count> name=<name>'");
    hash = hash_field.substr(16);
    count = cells_field.substr(6);
  }
  if (hash != plan.experiment_hash)
    throw FormatError(fmt::format(
        "{}: planned from another experiment (its hash {}, this file's {}): plan again with "
        "--plan, or choose another --out",
        path.string(), hash, plan.experiment_hash));
  if (count != std::to_string(plan.cells.size()))
    fail(2, fmt::format("says {} cells; the experiment has {}", count, plan.cells.size()));
  if (lines[2] != kManifestColumns)
    fail(3, fmt::format("expected the column names '{}'", kManifestColumns));
  for (std::size_t i = 0; i < plan.cells.size(); ++i) {
    if (3 + i >= lines.size())
      fail(lines.size() + 1,
           fmt::format("the manifest ends after {} of its {} cells", i, plan.cells.size()));
    if (lines[3 + i] != manifest_line(plan.cells[i]))
      fail(4 + i, fmt::format("damaged: expected the line of cell {} ({}), '{}'", i,
                              plan.cells[i].id, manifest_line(plan.cells[i])));
  }
  if (lines.size() > 3 + plan.cells.size())
    fail(4 + plan.cells.size(),
         fmt::format("more lines than the {} cells of the experiment", plan.cells.size()));
}

std::size_t find_cell(const Plan& plan, const std::string& choice) {
  const std::size_t n = plan.cells.size();
  if (!choice.empty() && choice.find_first_not_of("0123456789") == std::string::npos) {
    if (choice.size() > 18 || std::stoull(choice) >= n)
      throw std::invalid_argument(fmt::format(
          "--cell {}: out of range: the manifest has {} cells, 0 to {}", choice, n, n - 1));
    return static_cast<std::size_t>(std::stoull(choice));
  }
  for (const auto& c : plan.cells)
    if (c.id == choice) return c.index;
  throw std::invalid_argument(
      fmt::format("--cell {}: no cell has this id (ids are in manifest.tsv; an index 0 to {} "
                  "works too)",
                  choice, n - 1));
}

CellStatus cell_status(const Cell& cell, const fs::path& out_dir) {
  const fs::path dir = cell_dir(cell, out_dir);
  CellStatus s;
  const auto status = read_status_json(dir);
  if (status) {
    s.attempts = status->value("attempts", 0);
    s.runner = status->value("runner", "");
    s.cpu_s = status->value("cpu_s", 0.0);
    s.wall_s = status->value("wall_s", 0.0);
    s.message = status->value("message", "");
  }
  std::error_code ec;
  if (fs::exists(dir / "done", ec)) {
    s.state = CellState::done;
    return s;
  }
  if (!status) return s;  // missing
  const std::string state = status->value("state", "");
  if (state == "failed" || state == "done") {
    // "done" without its marker: stopped between the two writes.
    s.state = CellState::failed;
    if (state == "done") s.message = "stopped before its done marker was written";
    return s;
  }
  s.state = CellState::running;
  const long pid = status->value("pid", 0L);
  if (status->value("host", "") == host_name() && pid > 0 &&
      kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
    s.state = CellState::failed;
    s.message = fmt::format("stopped while running (process {} on {} is gone)", pid, host_name());
  }
  return s;
}

CellOutcome run_cell(const Experiment& ex, const Plan& plan, std::size_t index,
                     const fs::path& out_dir, const CellContext& context) {
  const Cell& cell = plan.cells.at(index);
  const fs::path dir = cell_dir(cell, out_dir);
  CellOutcome outcome;
  if (cell_status(cell, out_dir).state == CellState::done) {
    outcome.skipped = true;
    return outcome;
  }
  fs::create_directories(dir);
  const auto previous = read_status_json(dir);
  json status{{"id", cell.id},
              {"name", cell.name},
              {"kind", to_string(cell.kind)},
              {"state", "running"},
              {"attempts", (previous ? previous->value("attempts", 0) : 0) + 1},
              {"runner", context.runner},
              {"host", host_name()},
              {"pid", static_cast<long>(getpid())},
              {"started_utc", h5::utc_now_iso8601()}};
  write_status(dir, status);
  const auto cpu_now = [&] { return context.own_process ? process_cpu_s() : thread_cpu_s(); };
  const double cpu0 = cpu_now();
  const auto wall0 = std::chrono::steady_clock::now();
  const auto say = [&](const std::string& s) {
    if (context.progress) context.progress(s);
  };
  try {
    const std::string created = h5::utc_now_iso8601();
    json result{{"id", cell.id}, {"kind", to_string(cell.kind)}, {"name", cell.name}};
    if (cell.kind == CellKind::run) {
      const auto& run = ex.runs[cell.run];
      std::optional<capture::StrainMovie> base, strain;
      if (!context.base) base = prepare_source(ex.sources[run.source]);
      const auto& b = context.base ? *context.base : *base;
      if (!context.strain) strain = run_strain(b, ex.sources[run.source], run.params);
      const MappedRun m = map_run(ex, cell.run, b, context.strain ? *context.strain : *strain,
                                  out_dir, created, context.hdf5);
      result["metrics_row"] = m.metrics_row;
      result["resolved"] = m.resolved;
      result["frames"] = m.result.frames;
      result["map_ms"] = m.result.map_ms;
      result["um_per_strain"] = m.result.um_per_strain;
      result["metrics"] = metrics_json(m.result.metrics);
      result["activity_um"] = m.result.activity_um;
      say(fmt::format("run {} done: correlation {:.3f}", run.id,
                      m.result.metrics.strain_correlation));
    } else {
      std::vector<fs::path> files;
      outcome.perception =
          run_perception(ex, out_dir, context.threads, made_by(ex, created), files, say);
      json lines = json::array();
      for (const auto& t : outcome.perception)
        for (const auto& row : t.rows)
          if (row.result.inputs == "all") {
            const auto& r = row.result;
            lines.push_back({{"table", t.id},
                             {"degree", r.degree},
                             {"correct", r.correct},
                             {"tested", r.tested},
                             {"mean_r2", (r.r2[0] + r.r2[1] + r.r2[2]) / 3},
                             {"cascade_rms_mm", r.cascade_rms_mm}});
          }
      result["lines"] = lines;
      json names = json::array();
      for (const auto& f : files) names.push_back(f.lexically_relative(out_dir).string());
      result["files"] = names;
    }
    write_text_atomically(dir / "result.json", result.dump() + "\n");
    outcome.cpu_s = cpu_now() - cpu0;
    outcome.wall_s = seconds_since(wall0);
    status["state"] = "done";
    status["cpu_s"] = outcome.cpu_s;
    status["wall_s"] = outcome.wall_s;
    status["ended_utc"] = h5::utc_now_iso8601();
    write_status(dir, status);
    // Last: the marker is what makes the cell count as done.
    write_text_atomically(dir / "done", cell.id + "\n");
  } catch (const std::exception& e) {
    status["state"] = "failed";
    status["message"] = e.what();
    status["cpu_s"] = cpu_now() - cpu0;
    status["wall_s"] = seconds_since(wall0);
    status["ended_utc"] = h5::utc_now_iso8601();
    try {
      write_status(dir, status);
    } catch (const std::exception&) {
      // The cell's own error says more than a status that cannot be written.
    }
    throw;
  }
  return outcome;
}

MergeReport merge_experiment(const Experiment& ex, const Plan& plan, const fs::path& out_dir,
                             int threads) {
  MergeReport report;
  for (const auto& cell : plan.cells) {
    const CellStatus s = cell_status(cell, out_dir);
    if (s.state == CellState::done) continue;
    std::string note =
        fmt::format("{} {} ({}): {}", cell.index, cell.id, cell.name, to_string(s.state));
    if (!s.message.empty()) note += ": " + s.message;
    report.incomplete.push_back(note);
  }
  if (!report.incomplete.empty()) return report;

  std::vector<MappedRun> runs(ex.runs.size());
  for (const auto& cell : plan.cells) {
    const fs::path path = cell_dir(cell, out_dir) / "result.json";
    const json j = read_json_object(path, "cell result");
    const std::string where = path.string();
    if (json_field<std::string>(j, "id", where) != cell.id)
      throw FormatError(fmt::format("{}: is the result of another cell, not {}", where, cell.id));
    if (cell.kind == CellKind::run) {
      MappedRun& m = runs[cell.run];
      m.metrics_row = json_field<std::string>(j, "metrics_row", where);
      m.resolved = json_field<json>(j, "resolved", where);
      m.result.frames = json_field<std::int32_t>(j, "frames", where);
      m.result.map_ms = number_or_nan(j, "map_ms", where);
      m.result.um_per_strain = number_or_nan(j, "um_per_strain", where);
      m.result.metrics = metrics_from(json_field<json>(j, "metrics", where), where + " metrics");
      for (const auto& v : json_field<json>(j, "activity_um", where))
        m.result.activity_um.push_back(v.is_null() ? std::numeric_limits<double>::quiet_NaN()
                                                   : v.get<double>());
      const auto movie = m.resolved.value("movie", "");
      if (!movie.empty()) report.files.emplace_back(movie);
    } else {
      for (const auto& l : json_field<json>(j, "lines", where))
        report.perception.push_back(
            {json_field<std::string>(l, "table", where), json_field<int>(l, "degree", where),
             json_field<int>(l, "correct", where), json_field<int>(l, "tested", where),
             number_or_nan(l, "mean_r2", where), number_or_nan(l, "cascade_rms_mm", where)});
      for (const auto& f : json_field<json>(j, "files", where))
        report.files.push_back(out_dir / f.get<std::string>());
    }
  }
  report.files.push_back(out_dir / "manifest.tsv");
  report.files.push_back(out_dir / "experiment.json");
  write_merged(ex, runs, out_dir, made_by(ex, h5::utc_now_iso8601()), worker_count(threads),
               report.files);
  for (auto& m : runs) report.results.push_back(std::move(m.result));
  return report;
}

ExperimentStatus experiment_status(const Plan& plan, const fs::path& out_dir) {
  ExperimentStatus status;
  for (const auto& [kind, name] : kCellKindNames) {
    KindStatus k;
    k.kind = kind;
    for (const auto& cell : plan.cells) {
      if (cell.kind != kind) continue;
      ++k.cells;
      const CellStatus s = cell_status(cell, out_dir);
      switch (s.state) {
        case CellState::done:
          ++k.done;
          k.cpu_s += s.cpu_s;
          k.wall_s += s.wall_s;
          break;
        case CellState::running:
          ++k.running;
          break;
        case CellState::failed:
          ++k.failed;
          break;
        case CellState::missing:
          ++k.missing;
          break;
      }
      if (s.state != CellState::done) {
        std::string note =
            fmt::format("{} {} ({}): {}", cell.index, cell.id, cell.name, to_string(s.state));
        if (!s.runner.empty() && s.state != CellState::missing)
          note += fmt::format(" [{}, attempt {}]", s.runner, s.attempts);
        if (!s.message.empty()) note += ": " + s.message;
        status.notes.push_back(note);
      }
    }
    if (k.cells > 0) status.kinds.push_back(k);
  }
  return status;
}

}  // namespace tactile::experiments
