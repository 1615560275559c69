#pragma once
// Mapping experiments: a grid of sources x layouts x methods x parameters, checked whole before
// any work, run in parallel, written into one folder. The JSON schema is in docs/formats.md
// ("Experiment files"); tools/experiments/methods.json is an example.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/mapping/fidelity.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/tactile_movie.hpp"
#include "tactile/perception/report.hpp"

namespace tactile::experiments {

// "file": a strain movie file; "synthetic": capture's scene rendered to images and measured
// (render_sequence + measure_strain); "ground-truth": the scene's exact strain (ground_truth.hpp).
enum class SourceKind { file, synthetic, ground_truth };
inline constexpr std::array<Named<SourceKind>, 3> kSourceKindNames = {{
    {SourceKind::file, "file"},
    {SourceKind::synthetic, "synthetic"},
    {SourceKind::ground_truth, "ground-truth"},
}};
std::string to_string(SourceKind kind);

struct ExperimentSource {
  std::string name;
  SourceKind kind = SourceKind::file;
  std::filesystem::path path;                  // file
  capture::SceneSpec scene;                    // synthetic, ground-truth
  double grid_spacing_mm = 0.3;                // ground-truth
  double frame_rate_hz = 0;                    // known before any work: the file's or the scene's
  std::optional<capture::StrainMovie> loaded;  // file sources are read while checking
};

struct ExperimentRun {
  // "003-bump-stress-integrated-per-frame", then "-normalisation-peak" for each other parameter
  // that varies in the grid: also the movie's file name
  std::string id;
  std::size_t source = 0;
  std::size_t layout = 0;
  mapping::MappingParams params;
};

// Optional "perception" section: Table 2 of paper 2 computed from the tactile movies each
// mapping makes of the skin strain of the simulated fingertip's trials (capture's
// simulate_skin_strain; movie_signals.hpp), beside the simulated sensor's own Table 2.
struct ExperimentPerception {
  int trials = 20;                    // per feature and procedure, as `tactile perceive`
  std::vector<int> degrees = {1, 2};  // kernel exponents
  std::vector<double> footprints_mm;  // features kept (all curvatures, bumps and pits); empty: all
  std::uint64_t seed = 1;             // trial seeds, as `tactile perceive --seed`
  bool reference = true;              // also the simulated sensor's Table 2 on the same trials
  double grid_spacing_mm = 1.0;       // material grid of the skin strain
};

struct Experiment {
  std::string name;
  std::uint64_t seed = 1;
  std::string text;    // the JSON as given, copied into the output folder
  std::string origin;  // the file it came from
  bool write_movies = true;
  std::vector<ExperimentSource> sources;
  std::vector<movie::Layout> layouts;
  std::vector<std::filesystem::path> layout_files;  // the layouts read from files
  // Each layout as the file names it: a built-in name, or a layout file's path (a relative one
  // joined to the experiment file's folder).
  std::vector<std::string> layout_refs;
  std::vector<ExperimentRun> runs;
  std::optional<ExperimentPerception> perception;
  // The whole grid in words: "1 sources x 2 layouts x 1 methods x 2 parameter sets (layouts:
  // stress, latero; methods: integrated; normalisation: none, peak)".
  std::string grid;
};

// Parses and checks a whole experiment before any work: JSON syntax, unknown or missing fields,
// wrong types, no sources / layouts / methods, duplicate source names, unknown method, strain
// or normalisation, bad parameters, bad scenes, unreadable source files or layout files, a rate
// above a layout's maximum rate (incompatible layout and rate), a source filmed faster than a
// layout can play, a bad perception section (trials, degree, footprints, seed, reference, grid
// spacing; a layout with fewer than 6 columns; no strain-driven method). Relative paths are
// taken from base_dir. Throws tactile::FormatError naming
// `origin` and the problem.
Experiment parse_experiment(const std::string& text, const std::string& origin,
                            const std::filesystem::path& base_dir);
Experiment read_experiment(const std::filesystem::path& path);

struct RunResult {
  mapping::FidelityMetrics metrics;
  std::int32_t frames = 0;
  double map_ms = 0;
  double um_per_strain = 0;
  // Mean |deflection| over the contactors, one value per display frame (for activity plots).
  std::vector<double> activity_um;
};

// Table 2 from the movies of one mapping (a layout and a parameter set: the runs that differ
// only in their source share one), or of the simulated sensor (method "sensor").
struct PerceptionTable {
  std::string id;  // "00-stress-proportional-per-frame", "sensor"
  std::string layout, method, strain, normalisation;
  double gain_um_per_strain = 0, rate_hz = 0;
  std::vector<perception::TimedCascade> rows;  // as run_table2
};

// A line of the perception summary a command prints (Table 2 with all 76 inputs).
struct PerceptionLine {
  std::string table;
  int degree = 1, correct = 0, tested = 0;
  double mean_r2 = 0, cascade_rms_mm = 0;
};

struct ExperimentReport {
  std::vector<RunResult> results;            // in the order of Experiment::runs
  std::vector<PerceptionTable> perception;   // the sensor's first, when asked for
  std::vector<PerceptionLine> lines;         // of `perception`, as the merge reads them
  std::vector<std::filesystem::path> files;  // everything written
  double prepare_s = 0;                      // sources made or read
  double run_s = 0;                          // all mappings, metrics and movie files
  double perception_s = 0;                   // skin strain, movies, signals and Table 2s
  int threads = 1;
};

// The experiment's cells (cells.hpp) run on `threads` workers (0 = all cores), skipping those
// already done, then merged: writes into out_dir (created) manifest.tsv and cells/ (see
// cells.hpp), experiment.json (the input as given), resolved.json (every run's
// resolved parameters, layouts and provenance), metrics.csv, movies/<run id>.h5 (if
// write_movies), plots/correlation.png, plots/saturation.png and
// plots/activity-<source>-<layout>.png; with a perception section also
// perception/table2-<mapping>.csv per mapping (and table2-sensor.csv), perception/summary.csv
// and plots/perception.png; every plot also as .svg (common/chart.hpp). The same experiment gives
// the same files, whatever the thread count (up to the creation time). `progress` (optional) is
// called from worker threads with a short message.
ExperimentReport run_experiment(Experiment experiment, const std::filesystem::path& out_dir,
                                int threads,
                                const std::function<void(const std::string&)>& progress = {});

// What run_experiment does to run `run`'s movie before writing it: the experiment file as its
// input, the experiment, run and source named in its parameters, created at `created_utc`. A
// program that maps a run itself (the authoring window) stamps it so, to write the same file.
void stamp_run_provenance(const Experiment& ex, std::size_t run, movie::TactileMovie& movie,
                          const std::string& created_utc);
// Where run_experiment writes run `run`'s movie: out_dir/movies/<run id>.h5.
std::filesystem::path run_movie_path(const Experiment& ex, std::size_t run,
                                     const std::filesystem::path& out_dir);

// What run_experiment writes into out_dir (given by `option`), for a caller that must not write
// over the experiment's inputs: the files at its top, and the sub-folders whose files it names
// after runs, sources, layouts and mappings.
Output experiment_output(std::string option, const std::filesystem::path& out_dir);

// The perception section alone (run_experiment calls it after the runs): one Table 2 per distinct
// (layout, parameters) of the strain-driven runs ("profile" renders a capture scene's Gaussian
// surface, not the feature plates, and is left out), the sensor's first when asked for; files as
// above, appended to `files`. Throws std::runtime_error naming the mapping and trial when a
// movie shows no contact.
std::vector<PerceptionTable> run_perception(
    const Experiment& experiment, const std::filesystem::path& out_dir, int threads,
    const std::string& made_by, std::vector<std::filesystem::path>& files,
    const std::function<void(const std::string&)>& progress);

}  // namespace tactile::experiments
