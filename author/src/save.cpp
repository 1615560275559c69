// The authoring window's A/B as an experiment and its movies; see save.hpp.
#include "tactile/author/save.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/plain_name.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"
#include "tactile/movie/wav.hpp"

namespace tactile::author {

namespace fs = std::filesystem;

namespace {

// The distinct values of `value_of` over the mappings, in their order.
template <typename F>
nlohmann::json distinct(const std::vector<mapping::MapRequest>& mappings, F value_of) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& m : mappings) {
    const nlohmann::json v = value_of(m);
    if (std::find(list.begin(), list.end(), v) == list.end()) list.push_back(v);
  }
  return list;
}

// A layout as the experiment names it: built-in by name, a file by its absolute path (the
// experiment file may be read from another folder).
std::string layout_ref(const std::string& layout) {
  if (fs::path(layout).extension() != ".json") return layout;
  return fs::absolute(layout).lexically_normal().string();
}

// The run of `ex` that `outcome` is, checked: the grid's first or last run, whose resolved
// parameters must be the outcome's (else the experiment would not give the outcome's movie).
std::size_t run_of(const experiments::Experiment& ex, std::size_t index,
                   const MappingOutcome& outcome) {
  const experiments::ExperimentRun& run = ex.runs.at(index);
  const mapping::MappingParams p =
      mapping::resolve_mapping_params(run.params, ex.layouts[run.layout]);
  const mapping::MappingParams& q = outcome.params;
  const bool same = ex.layouts[run.layout].name == outcome.layout.name && p.method == q.method &&
                    p.gain_um_per_strain == q.gain_um_per_strain &&
                    p.normalisation == q.normalisation && p.peak_fraction == q.peak_fraction &&
                    p.rate_hz == q.rate_hz && p.strain == q.strain &&
                    p.accumulate.reference_frame == q.accumulate.reference_frame &&
                    p.slew_limit_um_per_s == q.slew_limit_um_per_s;
  if (!same) {
    throw std::logic_error(fmt::format("experiment run '{}' is not the mapping saved", run.id));
  }
  return index;
}

}  // namespace

std::string experiment_json(const std::string& name, const fs::path& strain_file,
                            const std::vector<mapping::MapRequest>& mappings) {
  if (mappings.empty()) throw std::invalid_argument("no mapping to save");
  if (const auto problem = plain_name_error("the experiment's name", name)) {
    throw std::invalid_argument(*problem);
  }
  nlohmann::ordered_json j;
  j["name"] = name;
  j["seed"] = 1;
  j["sources"] = nlohmann::json::array(
      {{{"name", "strain"}, {"file", fs::absolute(strain_file).lexically_normal().string()}}});
  j["layouts"] = distinct(mappings, [](const auto& m) { return layout_ref(m.layout); });
  j["methods"] = distinct(mappings, [](const auto& m) { return to_string(m.params.method); });
  nlohmann::ordered_json parameters;
  parameters["strain"] =
      distinct(mappings, [](const auto& m) { return to_string(m.params.strain); });
  // Only accumulated strain has a reference frame, and an experiment refuses one that no run
  // would use.
  if (std::any_of(mappings.begin(), mappings.end(), [](const auto& m) {
        return m.params.strain == mapping::StrainMode::accumulated;
      })) {
    parameters["reference_frame"] =
        distinct(mappings, [](const auto& m) { return m.params.accumulate.reference_frame; });
  }
  parameters["normalisation"] =
      distinct(mappings, [](const auto& m) { return to_string(m.params.normalisation); });
  parameters["peak_fraction"] =
      distinct(mappings, [](const auto& m) { return m.params.peak_fraction; });
  parameters["gain_um_per_strain"] =
      distinct(mappings, [](const auto& m) { return m.params.gain_um_per_strain; });
  const bool any_rate = std::any_of(mappings.begin(), mappings.end(),
                                    [](const auto& m) { return m.params.rate_hz.has_value(); });
  if (any_rate) {
    // One mapping sets a rate: each unset one plays at its layout's own, written out.
    parameters["rate_hz"] = distinct(mappings, [](const auto& m) {
      return m.params.rate_hz ? *m.params.rate_hz : movie::resolve_layout(m.layout).max_rate_hz;
    });
  }
  j["parameters"] = parameters;
  j["write_movies"] = true;
  return j.dump(2) + "\n";
}

Saved save_authoring(const fs::path& out_dir, const std::string& name, const fs::path& strain_file,
                     const MappingOutcome* a, const MappingOutcome& current) {
  for (const MappingOutcome* o : {a, &current}) {
    if (o != nullptr && !o->error.empty()) {
      throw std::invalid_argument("cannot save a mapping that failed: " + o->error);
    }
  }
  std::vector<mapping::MapRequest> requests;
  if (a != nullptr) requests.push_back(a->request);
  requests.push_back(current.request);
  Saved saved;
  saved.experiment = out_dir / (name + ".json");
  const std::string text = experiment_json(name, strain_file, requests);
  // Checked by the experiment library's reader before anything is written.
  const experiments::Experiment ex =
      experiments::parse_experiment(text, saved.experiment.string(), out_dir);
  std::vector<std::pair<const MappingOutcome*, std::size_t>> runs;
  if (a != nullptr) runs.emplace_back(a, run_of(ex, 0, *a));
  runs.emplace_back(&current, run_of(ex, ex.runs.size() - 1, current));
  // Nothing written over what the mappings read (the strain, a layout file typed in the window).
  const std::vector<Output> outputs = {
      output_folder("the save folder", out_dir, {saved.experiment.filename()}, {"movies"})};
  std::vector<NamedPath> inputs = {{"the strain movie", strain_file}};
  for (const auto& r : requests) {
    if (fs::path(r.layout).extension() == ".json") inputs.push_back({"a layout", r.layout});
  }
  refuse_output_over_input(outputs, inputs);
  fs::create_directories(out_dir / "movies");
  write_text_atomically(saved.experiment, text);
  const std::string created = h5::utc_now_iso8601();
  for (const auto& [outcome, index] : runs) {
    if (a != nullptr && outcome == &current && index == 0) break;  // A and the current are one
    movie::TactileMovie movie = outcome->movie;
    experiments::stamp_run_provenance(ex, index, movie, created);
    const fs::path path = experiments::run_movie_path(ex, index, out_dir);
    movie::write_tactile_movie(path, movie);
    saved.movies.push_back(path);
    saved.run_ids.push_back(ex.runs[index].id);
  }
  saved.hjif = fs::path(saved.movies.back()).replace_extension(".hjif");
  saved.wav = fs::path(saved.movies.back()).replace_extension(".wav");
  movie::write_hjif(current.movie, saved.hjif);
  movie::write_wav(current.movie, saved.wav);
  return saved;
}

ExperimentChoices choices_of(const experiments::Experiment& experiment) {
  const auto& ex = experiment;
  const auto source = std::find_if(ex.sources.begin(), ex.sources.end(), [](const auto& s) {
    return s.kind == experiments::SourceKind::file;
  });
  if (source == ex.sources.end()) {
    throw std::invalid_argument(
        fmt::format("{}: the experiment has no strain movie file among its sources (the window "
                    "maps a strain movie)",
                    ex.origin));
  }
  const auto source_index = static_cast<std::size_t>(source - ex.sources.begin());
  std::vector<const experiments::ExperimentRun*> runs;
  for (const auto& run : ex.runs)
    if (run.source == source_index) runs.push_back(&run);
  const auto request_of = [&](const experiments::ExperimentRun& run) {
    if (run.params.method == mapping::MappingMethod::profile) {
      throw std::invalid_argument(fmt::format(
          "{}: run '{}' uses method profile, which the window cannot map from a strain movie",
          ex.origin, run.id));
    }
    mapping::MapRequest r;
    r.strain = source->path;
    r.layout = ex.layout_refs.at(run.layout);
    r.params = run.params;
    return r;
  };
  ExperimentChoices choices;
  choices.strain_file = source->path;
  choices.current = request_of(*runs.back());
  if (runs.size() > 1) choices.a = request_of(*runs.front());
  return choices;
}

}  // namespace tactile::author
