// Running an experiment: sources prepared and runs mapped on a pool of threads, then the folder
// of movies, metrics, plots and configuration written.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "run_steps.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/ground_truth.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/version.hpp"
#include "tactile/experiments/cells.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"
#include "vocabulary.hpp"

namespace tactile::experiments {

namespace {

namespace fs = std::filesystem;

}  // namespace

std::string to_string(SourceKind kind) {
  return name_in(kSourceKindNames, kind);
}

capture::StrainMovie prepare_source(const ExperimentSource& s) {
  if (s.kind == SourceKind::file) return *s.loaded;
  if (s.kind == SourceKind::ground_truth)
    return capture::ground_truth_strain_movie(s.scene, s.grid_spacing_mm);
  const auto sequence = capture::render_sequence(s.scene);
  auto movie =
      capture::measure_strain(sequence.frames, sequence.calibration, s.scene.frame_rate_hz);
  // Measured from frames rendered in memory: no input file; the scene is in the parameters.
  auto settings = nlohmann::json::parse(movie.provenance.parameters_json);
  settings["scene"] = to_string(s.scene.scene);
  settings["speed_mm_per_s"] = s.scene.speed_mm_per_s;
  settings["seed"] = s.scene.seed;
  movie.provenance.parameters_json = settings.dump();
  return movie;
}

capture::StrainMovie run_strain(const capture::StrainMovie& base, const ExperimentSource& source,
                                const MappingParams& p) {
  if (p.strain != StrainMode::accumulated) return base;
  auto strain = accumulate_along_tracks(base, p.accumulate);
  if (strain.frames.empty()) {
    throw std::runtime_error(fmt::format(
        "source '{}': no frame shares three tracks with the reference frame", source.name));
  }
  return strain;
}

std::string made_by(const Experiment& ex, const std::string& created_utc) {
  return fmt::format("tactile {} experiment '{}' ({}), seed {}, {}", kVersion, ex.name, ex.origin,
                     ex.seed, created_utc);
}

nlohmann::json source_json(const ExperimentSource& s) {
  nlohmann::json j{
      {"name", s.name}, {"kind", to_string(s.kind)}, {"frame_rate_hz", s.frame_rate_hz}};
  if (s.kind == SourceKind::file) {
    j["file"] = s.path.string();
  } else {
    j["scene"] = {{"scene", to_string(s.scene.scene)},
                  {"frames", s.scene.frame_count},
                  {"frame_rate_hz", s.scene.frame_rate_hz},
                  {"speed_mm_per_s", s.scene.speed_mm_per_s},
                  {"height_mm", s.scene.feature_height_mm},
                  {"width_mm", s.scene.feature_width_mm},
                  {"contact_semi_x_mm", s.scene.contact_semi_x_mm},
                  {"noise", s.scene.noise_sigma},
                  {"seed", s.scene.seed}};
    if (s.kind == SourceKind::ground_truth) j["grid_spacing_mm"] = s.grid_spacing_mm;
  }
  return j;
}

namespace {

std::string strain_key(std::size_t source, const MappingParams& p) {
  return p.strain == StrainMode::accumulated
             ? fmt::format("{}:acc:{}:{}", source, p.accumulate.reference_frame,
                           p.accumulate.max_edge_ratio)
             : fmt::format("{}:frames", source);
}

}  // namespace

// The names run_experiment below and run_perception write: keep the three lists alike.
Output experiment_output(std::string option, const fs::path& out_dir) {
  return output_folder(std::move(option), out_dir,
                       {"experiment.json", "resolved.json", "metrics.csv", "manifest.tsv"},
                       {"movies", "plots", "perception", "cells", "slurm"});
}

void stamp_run_provenance(const Experiment& ex, std::size_t run, movie::TactileMovie& movie,
                          const std::string& created_utc) {
  // Made from the experiment file; which run of it, and which of its sources, is said with the
  // mapping's parameters.
  const ExperimentRun& r = ex.runs.at(run);
  movie.provenance.input = ex.origin;
  auto parameters = nlohmann::json::parse(movie.provenance.parameters_json);
  parameters["experiment"] = ex.name;
  parameters["run"] = r.id;
  parameters["source"] = ex.sources[r.source].name;
  movie.provenance.parameters_json = parameters.dump();
  movie.provenance.created_utc = created_utc;
}

fs::path run_movie_path(const Experiment& ex, std::size_t run, const fs::path& out_dir) {
  return out_dir / "movies" / (ex.runs.at(run).id + ".h5");
}

MappedRun map_run(const Experiment& ex, std::size_t index, const capture::StrainMovie& base,
                  const capture::StrainMovie& source, const fs::path& out_dir,
                  const std::string& created, std::mutex* hdf5) {
  const auto& run = ex.runs[index];
  const auto& layout = ex.layouts[run.layout];
  MappingParams params = run.params;
  params.program_version = kVersion;
  MappedRun out;
  const auto start = std::chrono::steady_clock::now();
  auto mapped = map_strain_frames(source, layout, params);
  auto& r = out.result;
  r.map_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  r.frames = mapped.movie.frame_count;
  r.um_per_strain = mapped.um_per_strain;
  r.metrics = mapped.um_per_strain > 0
                  ? fidelity(mapped.movie, source, mapped.placement, mapped.um_per_strain,
                             params.slew_limit_um_per_s, params.field)
                  : FidelityMetrics{};
  const auto n = static_cast<std::size_t>(layout.contactor_count());
  r.activity_um.resize(static_cast<std::size_t>(r.frames));
  for (std::size_t f = 0; f < r.activity_um.size(); ++f) {
    double sum = 0;
    for (std::size_t j = 0; j < n; ++j) sum += std::abs(mapped.movie.deflection_um[f * n + j]);
    r.activity_um[f] = sum / static_cast<double>(n);
  }
  std::string movie_file;
  if (ex.write_movies) {
    auto& movie = mapped.movie;
    stamp_run_provenance(ex, index, movie, created);
    const fs::path file = run_movie_path(ex, index, out_dir);
    fs::create_directories(file.parent_path());
    std::unique_lock<std::mutex> lock;
    if (hdf5) lock = std::unique_lock(*hdf5);
    movie::write_tactile_movie(file, movie);
    movie_file = file.string();
  }
  out.resolved["id"] = run.id;
  out.resolved["source"] = ex.sources[run.source].name;
  out.resolved["layout"] = layout.name;
  out.resolved["movie"] = movie_file;
  // The placement is the default one unless given; parameters_json records the one used.
  out.resolved["parameters"] = nlohmann::json::parse(
      parameters_json(run.params, run.params.placement.value_or(default_placement(base)),
                      r.um_per_strain / run.params.gain_um_per_strain));
  const auto& p = run.params;
  const auto& m = r.metrics;
  out.metrics_row = fmt::format(
      "{},{},{},{},{},{},{:g},{:g},{},{},{:.6f},{:.6g},{:.6g},{:.6f},{:.6f},{:.6g},{:.6g},{:.2f}",
      run.id, ex.sources[run.source].name, layout.name, to_string(p.method), to_string(p.strain),
      to_string(p.normalisation), p.gain_um_per_strain, p.rate_hz.value(), r.frames,
      m.compared_pairs, m.strain_correlation, m.strain_rms_error, m.source_strain_rms,
      m.saturated_fraction, m.slew_limited_fraction, m.rms_acceleration_um_per_s2,
      m.rms_deflection_um, r.map_ms);
  return out;
}

fs::path write_experiment_copy(const Experiment& ex, const fs::path& out_dir) {
  const fs::path path = out_dir / "experiment.json";
  write_text_atomically(path, ex.text);
  return path;
}

void write_merged(const Experiment& ex, const std::vector<MappedRun>& runs, const fs::path& out_dir,
                  const std::string& made_by_text, int threads, std::vector<fs::path>& files) {
  {
    nlohmann::json j;
    j["made_by"] = made_by_text;
    j["grid"] = ex.grid;
    j["program_version"] = kVersion;
    j["created_utc"] = made_by_text.substr(made_by_text.rfind(", ") + 2);
    j["experiment"] = ex.name;
    j["origin"] = ex.origin;
    j["seed"] = ex.seed;
    j["threads"] = threads;
    for (const auto& s : ex.sources) j["sources"].push_back(source_json(s));
    for (const auto& l : ex.layouts)
      j["layouts"].push_back(nlohmann::json::parse(movie::layout_to_json(l)));
    for (const auto& run : runs) j["runs"].push_back(run.resolved);
    const fs::path path = out_dir / "resolved.json";
    AtomicOstream out(path);
    out << j.dump(2) << '\n';
    csv::finish(out, path);
    files.push_back(path);
  }
  {
    const fs::path path = out_dir / "metrics.csv";
    AtomicOstream out(path);
    out << "# made by " << made_by_text << '\n'
        << "run,source,layout,method,strain,normalisation,gain_um_per_strain,rate_hz,frames,"
           "compared_pairs,strain_correlation,strain_rms_error,source_strain_rms,"
           "saturated_fraction,slew_limited_fraction,rms_acceleration_um_per_s2,"
           "rms_deflection_um,map_ms\n";
    for (const auto& run : runs) out << run.metrics_row << '\n';
    csv::finish(out, path);
    files.push_back(path);
  }
  std::vector<std::string> labels, legend = names_of(kMappingMethods);
  std::vector<double> correlation, saturation;
  std::vector<int> colours;
  for (std::size_t i = 0; i < ex.runs.size(); ++i) {
    const auto& run = ex.runs[i];
    labels.push_back(fmt::format(
        "{} {} {} {}{}", ex.sources[run.source].name, ex.layouts[run.layout].name,
        to_string(run.params.strain), to_string(run.params.normalisation),
        run.params.gain_um_per_strain != 1000 ? fmt::format(" g{:g}", run.params.gain_um_per_strain)
                                              : ""));
    correlation.push_back(runs[i].result.metrics.strain_correlation);
    saturation.push_back(runs[i].result.metrics.saturated_fraction);
    const auto m = std::find(kMappingMethods.begin(), kMappingMethods.end(), run.params.method);
    colours.push_back(static_cast<int>(m - kMappingMethods.begin()));
  }
  const std::string footer = "made by " + made_by_text;
  const fs::path plots = out_dir / "plots";
  fs::create_directories(plots);
  const auto keep = [&](const ChartFiles& f) { files.insert(files.end(), {f.png, f.svg}); };
  // The two bar charts show the same runs in the same colours; only the metric differs.
  BarChart bars{.labels = labels, .colours = colours, .legend = legend, .footer = footer};
  bars.title = fmt::format("{}: imposed vs source strain between neighbours", ex.name);
  bars.value_label = "correlation";
  bars.values = correlation;
  bars.min = -0.5;
  bars.max = 1.0;
  keep(write_bar_chart(plots / "correlation.png", bars));
  bars.title = fmt::format("{}: fraction of contactor-frames at the range limits", ex.name);
  bars.value_label = "saturated fraction";
  bars.values = saturation;
  bars.min = 0.0;
  keep(write_bar_chart(plots / "saturation.png", bars));
  // Activity: one plot per source and layout, one line per method and parameter set, so
  // the lines compared share the same skin and the same contactors.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < ex.runs.size(); ++i) {
    groups[{ex.runs[i].source, ex.runs[i].layout}].push_back(i);
  }
  for (const auto& [key, members] : groups) {
    const auto& first = ex.runs[members.front()];
    // Runs of one group may differ in rate; the time axis uses the first run's period.
    const double dt_s = 1.0 / first.params.rate_hz.value();
    XYChart chart{.title = fmt::format("{}: mean |deflection|, source {} on {}", ex.name,
                                       ex.sources[key.first].name, ex.layouts[key.second].name),
                  .x = {.label = "t (s)"},
                  .y = {.label = "mean |deflection| (um)", .min = 0},
                  .footer = footer,
                  .width = 1000,
                  .height = 500};
    for (const auto i : members) {
      const auto& p = ex.runs[i].params;
      ChartSeries& s = chart.series.emplace_back();
      s.label =
          fmt::format("{} {} {} gain {:g} ({:g} Hz)", to_string(p.method), to_string(p.strain),
                      to_string(p.normalisation), p.gain_um_per_strain, p.rate_hz.value());
      s.y = runs[i].result.activity_um;
      for (std::size_t k = 0; k < s.y.size(); ++k) s.x.push_back(static_cast<double>(k) * dt_s);
    }
    keep(write_line_chart(plots / fmt::format("activity-{}-{}.png", ex.sources[key.first].name,
                                              ex.layouts[key.second].name),
                          chart));
  }
}

// The one-machine run is the cells' plan, every cell run here on a pool of threads, and their
// merge: the same files a cluster's run gives.
ExperimentReport run_experiment(Experiment ex, const fs::path& out_dir, int threads,
                                const std::function<void(const std::string&)>& progress) {
  ExperimentReport report;
  report.threads = worker_count(threads);
  const auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  const Plan plan = plan_experiment(ex);
  write_manifest(ex, plan, out_dir);
  std::vector<std::size_t> pending_runs;
  std::optional<std::size_t> perception_cell;
  for (const auto& cell : plan.cells) {
    if (cell_status(cell, out_dir).state == CellState::done) continue;
    if (cell.kind == CellKind::run) pending_runs.push_back(cell.index);
    if (cell.kind == CellKind::perception) perception_cell = cell.index;
  }

  // 1. Sources the pending runs need, then the strain each distinct (source, strain) pair needs.
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::size_t> needed;
  for (const auto c : pending_runs) needed.push_back(ex.runs[plan.cells[c].run].source);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  std::vector<capture::StrainMovie> base(ex.sources.size());
  parallel_for(needed.size(), report.threads, [&](std::size_t k) {
    const std::size_t i = needed[k];
    base[i] = prepare_source(ex.sources[i]);
    say(fmt::format("source {} ready ({} strain frames)", ex.sources[i].name,
                    base[i].frames.size()));
  });
  std::map<std::string, std::size_t> key_index;
  std::vector<std::pair<std::size_t, MappingParams>> strain_jobs;
  for (const auto c : pending_runs) {
    const auto& run = ex.runs[plan.cells[c].run];
    if (key_index.emplace(strain_key(run.source, run.params), strain_jobs.size()).second) {
      strain_jobs.emplace_back(run.source, run.params);
    }
  }
  std::vector<capture::StrainMovie> strain(strain_jobs.size());
  parallel_for(strain_jobs.size(), report.threads, [&](std::size_t i) {
    const auto& [s, p] = strain_jobs[i];
    strain[i] = run_strain(base[s], ex.sources[s], p);
  });
  report.prepare_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // 2. Run cells, then the merge.
  t0 = std::chrono::steady_clock::now();
  std::mutex hdf5_mutex;  // the HDF5 library is not thread-safe as Debian builds it
  parallel_for(pending_runs.size(), report.threads, [&](std::size_t k) {
    const Cell& cell = plan.cells[pending_runs[k]];
    const auto& run = ex.runs[cell.run];
    CellContext context{.threads = 1,
                        .runner = "local",
                        .own_process = false,
                        .base = &base[run.source],
                        .strain = &strain[key_index.at(strain_key(run.source, run.params))],
                        .hdf5 = &hdf5_mutex,
                        .progress = progress};
    run_cell(ex, plan, cell.index, out_dir, context);
  });
  if (perception_cell) {
    const auto p0 = std::chrono::steady_clock::now();
    const auto outcome =
        run_cell(ex, plan, *perception_cell, out_dir,
                 {.threads = report.threads, .runner = "local", .progress = progress});
    report.perception = outcome.perception;
    report.perception_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - p0).count();
  }
  auto merged = merge_experiment(ex, plan, out_dir, report.threads);
  if (!merged.incomplete.empty()) {
    throw std::runtime_error(
        fmt::format("experiment '{}': cell {} did not finish", ex.name, merged.incomplete.front()));
  }
  report.results = std::move(merged.results);
  report.lines = std::move(merged.perception);
  report.files = std::move(merged.files);
  report.run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() -
                 report.perception_s;
  return report;
}

}  // namespace tactile::experiments
