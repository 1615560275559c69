// Experiment files: parsed and checked whole before any work starts.

#include "tactile/experiments/experiment.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/plain_name.hpp"
#include "tactile/common/value_checks.hpp"
#include "tactile/mapping/profile.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/limits.hpp"
#include "tactile/movie/movie_io.hpp"
#include "tactile/perception/recording.hpp"
#include "tactile/perception/sensor_scene.hpp"
#include "vocabulary.hpp"

namespace tactile::experiments {

namespace {

using nlohmann::json;

using Context = JsonOrigin;

// A non-empty array (a single value counts as an array of one).
std::vector<json> list(const Context& cx, const json& v, const std::string& what) {
  if (!v.is_array()) return {v};
  if (v.empty()) cx.fail(fmt::format("'{}' is an empty list", what));
  return {v.begin(), v.end()};
}

// A name that becomes part of a path (a folder, a movie, a plot) or of a manifest line.
std::string json_plain_name(const Context& cx, const json& v, const std::string& what) {
  std::string name = json_string(cx, v, what);
  if (const auto error = plain_name_error(what, name)) cx.fail(*error);
  return name;
}

// A mode's name parsed here, where it enters, with the file and field in the message.
template <typename Parse>
auto json_mode(const Context& cx, const json& v, const std::string& what, Parse parse) {
  const std::string name = json_string(cx, v, what);
  try {
    return parse(name);
  } catch (const std::invalid_argument& e) {
    cx.fail(fmt::format("{}: {}", what, e.what()));
  }
}

capture::SceneSpec scene_spec(const Context& cx, const json& j, const std::string& where,
                              std::uint64_t default_seed) {
  json_only_keys(cx, j, where,
                 {"scene", "frames", "frame_rate_hz", "speed_mm_per_s", "height_mm", "width_mm",
                  "contact_semi_x_mm", "noise", "seed"});
  capture::SceneSpec s;
  s.seed = default_seed;
  s.scene =
      json_mode(cx, json_required(cx, j, "scene", where), where + ".scene", capture::parse_scene);
  if (j.contains("frames")) {
    const auto n = json_integer(cx, j["frames"], where + ".frames");
    if (n < 2 || n > 100000) cx.fail(fmt::format("{}.frames = {} is not in 2..100000", where, n));
    s.frame_count = static_cast<int>(n);
  }
  // The ranges of `tactile synth`'s options, so a scene means the same wherever it is given; a
  // camera rate as a movie's.
  const auto number = [&](const char* key, double min, double max, double& out) {
    if (j.contains(key)) {
      const std::string what = where + "." + key;
      out = checks::in_range(json_number(cx, j[key], what), min, max, cx.origin, what);
    }
  };
  number("frame_rate_hz", 1, movie::kMaxMovieRateHz, s.frame_rate_hz);
  number("speed_mm_per_s", 0, 100, s.speed_mm_per_s);
  number("height_mm", 0, 5, s.feature_height_mm);
  number("width_mm", 0.1, 50, s.feature_width_mm);
  number("contact_semi_x_mm", 0.5, 20, s.contact_semi_x_mm);
  number("noise", 0, 128, s.noise_sigma);
  if (j.contains("seed")) {
    const auto seed = json_integer(cx, j["seed"], where + ".seed");
    if (seed < 0) cx.fail(fmt::format("{}.seed must not be negative", where));
    s.seed = static_cast<std::uint64_t>(seed);
  }
  try {
    capture::validate_scene(s);
  } catch (const std::invalid_argument& e) {
    cx.fail(fmt::format("{}: {}", where, e.what()));
  }
  return s;
}

ExperimentSource parse_source(const Context& cx, const json& j, std::size_t index,
                              std::uint64_t seed, const std::filesystem::path& base_dir) {
  const std::string where = fmt::format("sources[{}]", index);
  json_only_keys(cx, j, where, {"name", "file", "synthetic", "ground_truth", "grid_spacing_mm"});
  ExperimentSource s;
  s.name = json_plain_name(cx, json_required(cx, j, "name", where), where + ".name");
  const int kinds = static_cast<int>(j.contains("file")) +
                    static_cast<int>(j.contains("synthetic")) +
                    static_cast<int>(j.contains("ground_truth"));
  if (kinds != 1) {
    cx.fail(fmt::format("{} ('{}') needs exactly one of 'file', 'synthetic', 'ground_truth'", where,
                        s.name));
  }
  if (j.contains("grid_spacing_mm") && !j.contains("ground_truth")) {
    cx.fail(fmt::format("{}: 'grid_spacing_mm' applies to ground_truth sources only", where));
  }
  // Each synthetic source gets its own seed from the experiment's unless it names one.
  const std::uint64_t default_seed = seed + index;
  if (j.contains("file")) {
    s.kind = SourceKind::file;
    s.path = json_string(cx, j["file"], where + ".file");
    if (s.path.is_relative()) s.path = base_dir / s.path;
    try {
      s.loaded = capture::read_strain_movie(s.path);
    } catch (const std::exception& e) {
      cx.fail(fmt::format("{} ('{}'): {}", where, s.name, e.what()));
    }
    if (s.loaded->frames.empty()) {
      cx.fail(fmt::format("{} ('{}'): {} has no strain frames", where, s.name, s.path.string()));
    }
    s.frame_rate_hz = s.loaded->frame_rate_hz;
  } else if (j.contains("synthetic")) {
    s.kind = SourceKind::synthetic;
    s.scene = scene_spec(cx, j["synthetic"], where + ".synthetic", default_seed);
    s.frame_rate_hz = s.scene.frame_rate_hz;
  } else {
    s.kind = SourceKind::ground_truth;
    s.scene = scene_spec(cx, j["ground_truth"], where + ".ground_truth", default_seed);
    s.frame_rate_hz = s.scene.frame_rate_hz;
    if (j.contains("grid_spacing_mm")) {
      s.grid_spacing_mm = json_number(cx, j["grid_spacing_mm"], where + ".grid_spacing_mm");
      if (!(s.grid_spacing_mm >= 0.05 && s.grid_spacing_mm <= 5)) {
        cx.fail(
            fmt::format("{}.grid_spacing_mm = {} is not in [0.05, 5]", where, s.grid_spacing_mm));
      }
    }
  }
  return s;
}

// More runs than any study needs (each writes files and plots): a file asking for more is a
// mistake (lists pasted where a value was meant), refused before millions of runs are made.
constexpr std::size_t kMaxRuns = 100000;

void check_run_count(const Context& cx, std::size_t runs, const std::string& what) {
  if (runs > kMaxRuns) {
    cx.fail(fmt::format("{} make {} runs, more than the limit of {}", what, runs, kMaxRuns));
  }
}

// A value of a parameter list as a run's name and the grid's description give it: a mode's name
// or a number as a person writes it.
std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) return fmt::format("{:g}", v.get<double>());
  return v.dump();
}

// The parameter grid: every combination of the parameter lists, in a fixed order (the JSON key
// order is sorted), each with the text that tells it from the others in a run's name.
struct ParameterGrid {
  std::vector<MappingParams> params;
  // Per entry: "-normalisation-peak" for each parameter given more than one value (strain
  // apart, which every run's name states).
  std::vector<std::string> names;
  // "normalisation: none, peak" for each parameter given more than one value, strain included.
  std::vector<std::string> varying;
};

ParameterGrid parameter_grid(const Context& cx, const json& j) {
  static const std::set<std::string> known = {
      "gain_um_per_strain", "normalisation",       "peak_fraction",       "rate_hz", "strain",
      "reference_frame",    "slew_limit_um_per_s", "min_triangle_quality"};
  json_only_keys(cx, j, "parameters", known);
  std::vector<MappingParams> grid(1);
  std::vector<std::string> names(1);
  std::vector<std::string> varying;
  for (const auto& [key, value] : j.items()) {
    const std::string what = "parameters." + key;
    const auto values = list(cx, value, what);
    // Checked before the product is built: 3000 x 8000 values would be 24 million runs.
    check_run_count(cx, grid.size() * values.size(), "the parameter lists");
    const bool varies = values.size() > 1;
    if (varies) {
      std::vector<std::string> texts;
      for (const auto& v : values) texts.push_back(value_text(v));
      varying.push_back(fmt::format("{}: {}", key, fmt::join(texts, ", ")));
    }
    std::vector<MappingParams> next;
    std::vector<std::string> next_names;
    for (const auto& v : values) {
      for (std::size_t g = 0; g < grid.size(); ++g) {
        MappingParams p = grid[g];
        next_names.push_back(varies && key != "strain"
                                 ? fmt::format("{}-{}-{}", names[g], key, value_text(v))
                                 : names[g]);
        // Ranges as `tactile map`'s options; the mapping checks the finer rules (a playable
        // rate, a positive gain) for the run.
        const auto number = [&](double min, double max) {
          return checks::in_range(json_number(cx, v, what), min, max, cx.origin, what);
        };
        if (key == "gain_um_per_strain") p.gain_um_per_strain = number(-1e6, 1e6);
        if (key == "peak_fraction") p.peak_fraction = number(0, 1);
        if (key == "rate_hz") p.rate_hz = number(1, movie::kMaxPlayableRateHz);
        if (key == "slew_limit_um_per_s") p.slew_limit_um_per_s = number(0, 1e9);
        if (key == "min_triangle_quality") p.field.min_triangle_quality = number(0, 1);
        if (key == "normalisation") p.normalisation = json_mode(cx, v, what, parse_normalisation);
        if (key == "strain") p.strain = json_mode(cx, v, what, parse_strain_mode);
        if (key == "reference_frame") {
          p.accumulate.reference_frame = static_cast<std::int32_t>(
              checks::int_in_range(json_integer(cx, v, what), -1, 100000000, cx.origin, what));
        }
        next.push_back(p);
      }
    }
    grid = std::move(next);
    names = std::move(next_names);
  }
  // Only accumulated strain has a reference frame: with no such run, the value was ignored
  // and an experiment said to vary it ran the same mapping.
  if (j.contains("reference_frame") &&
      std::none_of(grid.begin(), grid.end(),
                   [](const MappingParams& p) { return p.strain == StrainMode::accumulated; })) {
    cx.fail(
        "parameters.reference_frame is used only by strain 'accumulated', and no run has it "
        "(add \"strain\": [\"accumulated\"] to parameters, or remove reference_frame)");
  }
  return {std::move(grid), std::move(names), std::move(varying)};
}

ExperimentPerception parse_perception(const Context& cx, const json& j) {
  json_only_keys(cx, j, "perception",
                 {"trials", "degree", "footprints_mm", "seed", "reference", "grid_spacing_mm"});
  ExperimentPerception p;
  if (j.contains("trials")) {
    const auto n = json_integer(cx, j["trials"], "perception.trials");
    if (n < 2 || n > 1000) cx.fail(fmt::format("perception.trials = {} is not in 2..1000", n));
    p.trials = static_cast<int>(n);
  }
  if (j.contains("degree")) {
    p.degrees.clear();
    for (const auto& v : list(cx, j["degree"], "perception.degree")) {
      const auto d = json_integer(cx, v, "perception.degree");
      if (d != 1 && d != 2) cx.fail(fmt::format("perception.degree {} is not 1 or 2", d));
      if (std::find(p.degrees.begin(), p.degrees.end(), d) != p.degrees.end())
        cx.fail(fmt::format("perception.degree {} is given twice", d));
      p.degrees.push_back(static_cast<int>(d));
    }
  }
  if (j.contains("footprints_mm")) {
    std::set<double> paper;
    for (const auto& f : perception::paper_features()) paper.insert(f.footprint_mm);
    for (const auto& v : list(cx, j["footprints_mm"], "perception.footprints_mm")) {
      const double mm = json_number(cx, v, "perception.footprints_mm");
      if (!paper.contains(mm))
        cx.fail(
            fmt::format("perception.footprints_mm: {:g} is not a footprint of the paper's "
                        "plates ({})",
                        mm, fmt::join(paper, ", ")));
      if (std::find(p.footprints_mm.begin(), p.footprints_mm.end(), mm) != p.footprints_mm.end())
        cx.fail(fmt::format("perception.footprints_mm: {:g} is given twice", mm));
      p.footprints_mm.push_back(mm);
    }
  }
  if (j.contains("seed")) {
    const auto seed = json_integer(cx, j["seed"], "perception.seed");
    if (seed < 0) cx.fail("perception.seed must not be negative");
    p.seed = static_cast<std::uint64_t>(seed);
  }
  if (j.contains("reference")) {
    if (!j["reference"].is_boolean()) cx.fail("'perception.reference' must be true or false");
    p.reference = j["reference"].get<bool>();
  }
  if (j.contains("grid_spacing_mm")) {
    p.grid_spacing_mm = json_number(cx, j["grid_spacing_mm"], "perception.grid_spacing_mm");
    if (!(p.grid_spacing_mm >= 0.25 && p.grid_spacing_mm <= 3))
      cx.fail(
          fmt::format("perception.grid_spacing_mm = {:g} is not in [0.25, 3]", p.grid_spacing_mm));
  }
  return p;
}

}  // namespace

Experiment parse_experiment(const std::string& text, const std::string& origin,
                            const std::filesystem::path& base_dir) {
  const Context cx{origin};
  const json j = parse_json(cx, text);
  json_only_keys(cx, j, "the experiment",
                 {"name", "seed", "sources", "layouts", "methods", "parameters", "write_movies",
                  "perception"});
  Experiment ex;
  ex.text = text;
  ex.origin = origin;
  ex.name = json_plain_name(cx, json_required(cx, j, "name", "the experiment"), "name");
  const auto seed = json_integer(cx, json_required(cx, j, "seed", "the experiment"), "seed");
  if (seed < 0) cx.fail("'seed' must not be negative");
  ex.seed = static_cast<std::uint64_t>(seed);
  if (j.contains("write_movies")) {
    if (!j["write_movies"].is_boolean()) cx.fail("'write_movies' must be true or false");
    ex.write_movies = j["write_movies"].get<bool>();
  }

  const auto& sources = json_required(cx, j, "sources", "the experiment");
  if (!sources.is_array() || sources.empty()) cx.fail("'sources' must be a non-empty list");
  std::set<std::string> names;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    ex.sources.push_back(parse_source(cx, sources[i], i, ex.seed, base_dir));
    if (!names.insert(ex.sources.back().name).second) {
      cx.fail(fmt::format("two sources are named '{}'", ex.sources.back().name));
    }
  }
  const auto& layouts = json_required(cx, j, "layouts", "the experiment");
  if (!layouts.is_array() || layouts.empty()) cx.fail("'layouts' must be a non-empty list");
  for (std::size_t i = 0; i < layouts.size(); ++i) {
    std::string ref = json_string(cx, layouts[i], fmt::format("layouts[{}]", i));
    if (std::filesystem::path(ref).extension() == ".json" &&
        std::filesystem::path(ref).is_relative()) {
      ref = (base_dir / ref).string();
    }
    if (std::filesystem::path(ref).extension() == ".json") ex.layout_files.emplace_back(ref);
    ex.layout_refs.push_back(ref);
    try {
      ex.layouts.push_back(movie::resolve_layout(ref));
    } catch (const std::exception& e) {
      cx.fail(fmt::format("layouts[{}]: {}", i, e.what()));
    }
  }
  const auto& methods = json_required(cx, j, "methods", "the experiment");
  if (!methods.is_array() || methods.empty()) cx.fail("'methods' must be a non-empty list");
  std::vector<MappingMethod> method_list;
  for (std::size_t i = 0; i < methods.size(); ++i) {
    const std::string what = fmt::format("methods[{}]", i);
    method_list.push_back(json_mode(cx, methods[i], what, parse_mapping_method));
  }
  const ParameterGrid grid = j.contains("parameters")
                                 ? parameter_grid(cx, j["parameters"])
                                 : ParameterGrid{std::vector<MappingParams>(1), {""}, {}};
  const std::string counts =
      fmt::format("{} sources x {} layouts x {} methods x {} parameter sets", ex.sources.size(),
                  ex.layouts.size(), method_list.size(), grid.params.size());
  check_run_count(
      cx, ex.sources.size() * ex.layouts.size() * method_list.size() * grid.params.size(), counts);
  std::vector<std::string> layout_names, method_names;
  for (const auto& layout : ex.layouts) layout_names.push_back(layout.name);
  for (const auto& method : method_list) method_names.push_back(to_string(method));
  ex.grid = fmt::format("{} (layouts: {}; methods: {}{}{})", counts, fmt::join(layout_names, ", "),
                        fmt::join(method_names, ", "), grid.varying.empty() ? "" : "; ",
                        fmt::join(grid.varying, "; "));

  // Every run checked against its layout and source now, so nothing fails halfway.
  for (std::size_t s = 0; s < ex.sources.size(); ++s) {
    for (std::size_t l = 0; l < ex.layouts.size(); ++l) {
      const auto& source = ex.sources[s];
      const auto& layout = ex.layouts[l];
      if (source.frame_rate_hz > layout.max_rate_hz) {
        cx.fail(fmt::format(
            "source '{}' runs at {:g} Hz, faster than layout '{}' can play ({:g} Hz maximum "
            "rate): its frames would be dropped; resample the source first",
            source.name, source.frame_rate_hz, layout.name, layout.max_rate_hz));
      }
      for (const auto& method : method_list) {
        for (std::size_t g = 0; g < grid.params.size(); ++g) {
          MappingParams p = grid.params[g];
          p.method = method;
          ExperimentRun run;
          run.source = s;
          run.layout = l;
          // Named by every parameter that varies, so that no two runs share a name.
          run.id = fmt::format("{:03}-{}-{}-{}-{}{}", ex.runs.size(), source.name, layout.name,
                               to_string(method), to_string(p.strain), grid.names[g]);
          if (p.method == MappingMethod::profile) {
            if (source.kind == SourceKind::file) {
              cx.fail(
                  fmt::format("run {}: method 'profile' needs a scene, but source '{}' is a "
                              "file (use a synthetic or ground_truth source)",
                              run.id, source.name));
            }
            p.profile = profile_of_scene(source.scene);
          }
          try {
            p = resolve_mapping_params(p, layout);
          } catch (const std::invalid_argument& e) {
            cx.fail(fmt::format("run {}: {}", run.id, e.what()));
          }
          if (p.strain == StrainMode::accumulated && source.loaded &&
              source.loaded->tracks.empty()) {
            cx.fail(
                fmt::format("run {}: source '{}' has no tracks; strain 'accumulated' needs them",
                            run.id, source.name));
          }
          run.params = p;
          ex.runs.push_back(std::move(run));
        }
      }
    }
  }
  if (j.contains("perception")) {
    ex.perception = parse_perception(cx, j["perception"]);
    if (std::all_of(method_list.begin(), method_list.end(),
                    [](MappingMethod m) { return m == MappingMethod::profile; }))
      cx.fail(
          "perception: needs a strain-driven method (proportional or integrated); 'profile' "
          "renders a scene's surface, not the feature plates");
    for (const auto& layout : ex.layouts)
      if (layout.cols < perception::kElectrodeClusterCount)
        cx.fail(fmt::format(
            "perception: layout '{}' has {} columns, fewer than the {} distal-proximal clusters",
            layout.name, layout.cols, perception::kElectrodeClusterCount));
  }
  return ex;
}

Experiment read_experiment(const std::filesystem::path& path) {
  return parse_experiment(read_json_text(path, "experiment file"), path.string(),
                          path.parent_path());
}

}  // namespace tactile::experiments
