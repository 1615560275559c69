// The perception section of an experiment: Table 2 of paper 2 from each mapping's movies of the
// simulated fingertip's skin strain, beside the simulated sensor's own (see experiment.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>

#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/experiments/sensor_strain.hpp"
#include "tactile/perception/movie_signals.hpp"
#include "vocabulary.hpp"

namespace tactile::experiments {

namespace {

namespace fs = std::filesystem;
using perception::Procedure;

constexpr std::array<Procedure, perception::kProcedureCount> kProcedures = {
    Procedure::static_contact, Procedure::distal_proximal, Procedure::radial_ulnar,
    Procedure::roll};

struct Mapping {
  PerceptionTable table;
  std::size_t layout = 0;
  MappingParams params;
};

// One mapping per distinct (layout, parameters) among the strain-driven runs, in run order.
std::vector<Mapping> distinct_mappings(const Experiment& ex) {
  std::vector<Mapping> mappings;
  std::set<std::string> seen;
  for (const auto& run : ex.runs) {
    if (run.params.method == MappingMethod::profile) continue;
    const std::string key =
        fmt::format("{}:{}", run.layout, parameters_json(run.params, Placement{}));
    if (!seen.insert(key).second) continue;
    Mapping m;
    m.layout = run.layout;
    m.params = run.params;
    const auto& layout = ex.layouts[run.layout];
    const std::string method = to_string(run.params.method);
    const std::string strain = to_string(run.params.strain);
    m.table = {fmt::format("{:02}-{}-{}-{}", mappings.size(), layout.name, method, strain),
               layout.name,
               method,
               strain,
               to_string(run.params.normalisation),
               run.params.gain_um_per_strain,
               run.params.rate_hz.value(),
               {}};
    mappings.push_back(std::move(m));
  }
  return mappings;
}

// Keeps only the first and last frame of every run of frames whose edges all change alike
// (within 1e-12: free air, a converged static hold, a flat plate sliding before the feature
// arrives). The mapping resamples linearly between strain frames, so the movie does not change,
// and building strain fields is most of the cost of a perception run.
capture::StrainMovie without_repeats(capture::StrainMovie movie) {
  const auto same = [](const capture::StrainFrame& a, const capture::StrainFrame& b) {
    if (a.edges.size() != b.edges.size()) return false;
    for (std::size_t e = 0; e < a.edges.size(); ++e)
      if (std::abs(a.edges[e].rel_change - b.edges[e].rel_change) > 1e-12) return false;
    return true;
  };
  const auto& frames = movie.frames;
  std::vector<char> keep(frames.size(), 1);
  for (std::size_t k = 1; k + 1 < frames.size(); ++k)
    keep[k] = !(same(frames[k - 1], frames[k]) && same(frames[k], frames[k + 1]));
  std::vector<capture::StrainFrame> kept;
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (keep[k]) kept.push_back(std::move(movie.frames[k]));
  movie.frames = std::move(kept);
  return movie;
}

const char* curvature_name(perception::Curvature c) {
  constexpr const char* names[] = {"planar", "conical", "spherical"};
  return names[static_cast<int>(c)];
}

void write_summary(const fs::path& path, const std::vector<PerceptionTable>& tables,
                   const std::string& made_by) {
  std::string header =
      "mapping,layout,method,strain,normalisation,gain_um_per_strain,rate_hz,degree";
  for (const char* inputs : {"all", "static", "dp", "ru", "roll"})
    header += fmt::format(",accuracy_{}", inputs);
  header += ",r2_planar_all,r2_conical_all,r2_spherical_all,cascade_rms_all_mm";
  auto out = csv::open_with_header(path, "# made by " + made_by + "\n" + header);
  for (const auto& t : tables) {
    std::set<int> degrees;
    for (const auto& row : t.rows) degrees.insert(row.result.degree);
    for (int degree : degrees) {
      out << fmt::format("{},{},{},{},{},{:g},{:g},{}", t.id, t.layout, t.method, t.strain,
                         t.normalisation, t.gain_um_per_strain, t.rate_hz, degree);
      const CascadeResult* all = nullptr;
      for (const char* inputs : {"all", "static", "dp", "ru", "roll"})
        for (const auto& row : t.rows)
          if (row.result.degree == degree && row.result.inputs == inputs) {
            const auto& r = row.result;
            out << fmt::format(",{:.4f}", r.tested ? double(r.correct) / r.tested : 0.0);
            if (r.inputs == "all") all = &r;
          }
      for (double v : all->r2) out << fmt::format(",{:.4f}", v);
      out << fmt::format(",{:.4f}\n", all->cascade_rms_mm);
    }
  }
  csv::finish(out, path);
}

}  // namespace

std::vector<PerceptionTable> run_perception(
    const Experiment& ex, const fs::path& out_dir, int threads, const std::string& made_by,
    std::vector<fs::path>& files, const std::function<void(const std::string&)>& progress) {
  const ExperimentPerception& setup = ex.perception.value();
  const auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  std::vector<perception::SurfaceFeature> features;
  for (const auto& f : perception::paper_features())
    if (setup.footprints_mm.empty() ||
        std::find(setup.footprints_mm.begin(), setup.footprints_mm.end(), f.footprint_mm) !=
            setup.footprints_mm.end())
      features.push_back(f);
  std::vector<Mapping> mappings = distinct_mappings(ex);
  bool per_frame = false, from_rest = false;
  for (const auto& m : mappings)
    (m.params.strain == StrainMode::accumulated ? from_rest : per_frame) = true;

  // The skin grid covers every layout at physical size (the default placement centres it on the
  // pad), half a grid step beyond its outer contactors: the mappings sample nothing else, and the
  // grid's size is most of the cost.
  experiments::SkinStrainOptions skin;
  skin.grid_spacing_mm = setup.grid_spacing_mm;
  const auto half_extent = [&](double half_mm) {
    return setup.grid_spacing_mm * std::ceil(half_mm / setup.grid_spacing_mm + 0.5);
  };
  skin.half_length_mm = skin.half_width_mm = 0;
  for (const auto& l : ex.layouts) {
    skin.half_length_mm =
        std::max(skin.half_length_mm, half_extent(0.5 * (l.cols - 1) * l.pitch_x_mm));
    skin.half_width_mm =
        std::max(skin.half_width_mm, half_extent(0.5 * (l.rows - 1) * l.pitch_y_mm));
  }

  // One sample per feature and trial for every mapping (and the sensor); each job makes the
  // four procedures' skin strain once and maps it with every mapping.
  const std::size_t count = features.size() * static_cast<std::size_t>(setup.trials);
  PerceptionDataset empty;
  empty.names = perception_input_names();
  std::vector<PerceptionDataset> datasets(mappings.size() + 1, empty);
  for (auto& d : datasets) d.samples.resize(count);
  const ContactOptions contact = movie_contact_options();
  std::atomic<std::size_t> done{0};
  say(fmt::format("perception: {} features x {} trials x {} procedures, {} mappings{}",
                  features.size(), setup.trials, perception::kProcedureCount, mappings.size(),
                  setup.reference ? " and the simulated sensor" : ""));
  parallel_for(count, threads, [&](std::size_t k) {
    const auto& feature = features[k / static_cast<std::size_t>(setup.trials)];
    const int trial = static_cast<int>(k % static_cast<std::size_t>(setup.trials));
    for (auto& d : datasets) {
      auto& s = d.samples[k];
      s.feature = static_cast<int>(k / static_cast<std::size_t>(setup.trials));
      s.trial = trial;
      s.curvature = static_cast<int>(feature.curvature);
      s.footprint_mm = feature.signed_footprint_mm();
    }
    for (Procedure p : kProcedures) {
      const std::uint64_t seed = simulated_trial_seed(feature, p, trial, setup.seed);
      if (setup.reference) {
        const auto in = procedure_inputs(perception::simulate_trial(feature, p, seed), p);
        auto& inputs = datasets.back().samples[k].inputs;
        inputs.insert(inputs.end(), in.begin(), in.end());
      }
      experiments::SkinStrainOptions o = skin;
      std::optional<capture::StrainMovie> strain[2];
      if (per_frame)
        strain[0] = without_repeats(experiments::simulate_skin_strain(feature, p, seed, {}, o));
      o.from_rest = true;
      if (from_rest)
        strain[1] = without_repeats(experiments::simulate_skin_strain(feature, p, seed, {}, o));
      for (std::size_t m = 0; m < mappings.size(); ++m) {
        const auto& source = *strain[mappings[m].params.strain == StrainMode::accumulated ? 1 : 0];
        const std::string what =
            fmt::format("perception, mapping {}, {} {:+g} mm, {} trial {}", mappings[m].table.id,
                        curvature_name(feature.curvature), feature.signed_footprint_mm(),
                        perception::procedure_name(p), trial);
        try {
          const auto movie =
              map_strain_frames(source, ex.layouts[mappings[m].layout], mappings[m].params).movie;
          const auto in = procedure_inputs(movie_signals(movie, what), p, contact);
          auto& inputs = datasets[m].samples[k].inputs;
          inputs.insert(inputs.end(), in.begin(), in.end());
        } catch (const std::exception& e) {
          const std::string message = e.what();
          throw std::runtime_error(
              message.starts_with(what) ? message : fmt::format("{}: {}", what, message));
        }
      }
    }
    const std::size_t n = ++done;
    if (n % std::max<std::size_t>(1, count / 10) == 0 || n == count)
      say(fmt::format("perception: {} of {} feature trials done", n, count));
  });

  std::vector<PerceptionTable> tables;
  if (setup.reference) tables.push_back({"sensor", "-", "sensor", "-", "-", 0, 0, {}});
  for (auto& m : mappings) tables.push_back(std::move(m.table));
  const fs::path dir = out_dir / "perception";
  fs::create_directories(dir);
  for (std::size_t t = 0; t < tables.size(); ++t) {
    // datasets: the mappings', then the sensor's; tables: the sensor's first when asked for.
    const auto& d = datasets[!setup.reference ? t : t == 0 ? mappings.size() : t - 1];
    tables[t].rows = run_table2(d, split_per_block(d), setup.degrees);
    const fs::path path = dir / fmt::format("table2-{}.csv", tables[t].id);
    write_table2_csv(path, tables[t].rows);
    files.push_back(path);
    const fs::path by_footprint = dir / fmt::format("accuracy_by_footprint-{}.csv", tables[t].id);
    write_accuracy_by_footprint_csv(by_footprint, tables[t].rows);
    files.push_back(by_footprint);
    for (const auto& row : tables[t].rows)
      say(fmt::format("perception {}: {}", tables[t].id, table2_line(row)));
  }
  const fs::path summary = dir / "summary.csv";
  write_summary(summary, tables, made_by);
  files.push_back(summary);

  // Accuracy with all 76 inputs, one bar per mapping and exponent, coloured by method.
  std::vector<std::string> labels, legend = {"sensor", "proportional", "integrated"};
  std::vector<double> accuracy;
  std::vector<int> colours;
  for (const auto& t : tables)
    for (const auto& row : t.rows)
      if (row.result.inputs == "all") {
        labels.push_back(t.method == "sensor"
                             ? fmt::format("simulated sensor exp {}", row.result.degree)
                             : fmt::format("{} {} {} {} exp {}", t.layout, t.strain,
                                           t.normalisation, t.method, row.result.degree));
        accuracy.push_back(row.result.tested ? double(row.result.correct) / row.result.tested
                                             : 0.0);
        const auto it = std::find(legend.begin(), legend.end(), t.method);
        colours.push_back(static_cast<int>(it - legend.begin()));
      }
  fs::create_directories(out_dir / "plots");
  const ChartFiles plot = write_bar_chart(
      out_dir / "plots" / "perception.png",
      {.title = fmt::format("{}: curvature classified from movies (all 76 inputs)", ex.name),
       .value_label = "fraction of held-out trials correct",
       .labels = labels,
       .values = accuracy,
       .colours = colours,
       .legend = legend,
       .min = 0.0,
       .max = 1.0,
       .footer = "made by " + made_by});
  files.insert(files.end(), {plot.png, plot.svg});
  return tables;
}

}  // namespace tactile::experiments
