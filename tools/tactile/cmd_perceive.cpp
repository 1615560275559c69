// `tactile perceive`: the perception evaluation of paper 2 on the simulated fingertip sensor
// (Table 2 and Figure 7), and the same signal analysis on real BioTac-style recordings.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include "command.hpp"
#include "mode_option.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "progress.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/report.hpp"
#include "tactile/perception/seeds.hpp"
#include "tactile/perception/sensor_model.hpp"

namespace tactile::cli {
namespace {

constexpr const char* kCurvatureNames[3] = {"planar", "conical", "spherical"};

// The *_bio.csv recordings of `dir`, in name order.
std::vector<std::filesystem::path> recording_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".csv" && e.path().stem().string().ends_with("_bio"))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw std::runtime_error(fmt::format("{}: no *_bio.csv recordings", dir.string()));
  return files;
}

// Every recording of `files` with the BioTac header: read, segment, window, HHT; one CSV row
// each.
int analyse_recordings(const std::vector<std::filesystem::path>& files,
                       const std::filesystem::path& out_dir) {
  perception::ContactOptions o;
  o.baseline_at = perception::ContactOptions::BaselineAt::end;  // they begin in contact
  o.feature_from_kinematics = false;                            // textures: all contact is feature
  const auto names = perception::procedure_input_names(perception::Procedure::distal_proximal);
  std::string header =
      "file,rows,duration_s,baseline_pdc,threshold,contact_begin_s,contact_end_s,"
      "starts_in_contact,peak_pdc";
  for (const auto& n : names) header += "," + n.substr(3);  // drop the "dp." prefix
  const auto path = out_dir / "recordings.csv";
  auto out = csv::open_with_header(path, header);
  int failed = 0;
  for (const auto& f : files) {
    try {
      const auto r = perception::read_sensor_csv(f);
      const auto c = perception::find_contact(r, o);
      const auto in = perception::procedure_inputs(r, perception::Procedure::distal_proximal, o);
      const double peak = *std::max_element(r.pressure.begin(), r.pressure.end());
      out << fmt::format("{},{},{:.2f},{:.1f},{:.2f},{:.2f},{:.2f},{},{:g}", f.filename().string(),
                         r.rows(), r.rows() / r.rate_hz, c.baseline_pressure, c.threshold,
                         c.begin / r.rate_hz, c.end / r.rate_hz, c.starts_in_contact ? 1 : 0, peak);
      for (double v : in) out << fmt::format(",{:.4g}", v);
      out << '\n';
      fmt::print(
          "{}: {} rows ({:.2f} s), baseline pdc {:.1f} (from the end), contact {:.2f}-{:.2f} s{}, "
          "peak pdc {:g}; window means pdc {:.1f} / {:.1f}; mean IF of IMF1 {:.0f} Hz (first "
          "250 ms), {:.0f} Hz (last 250 ms)\n",
          f.filename().string(), r.rows(), r.rows() / r.rate_hz, c.baseline_pressure,
          c.begin / r.rate_hz, c.end / r.rate_hz, c.starts_in_contact ? " (starts in contact)" : "",
          peak, in[0], in[7], in[21], in[22]);
    } catch (const std::exception& e) {
      ++failed;
      fmt::print(stderr, "tactile perceive: {}\n", e.what());
    }
  }
  // A table of no recording is no result: the recordings.csv of an earlier run stays.
  if (failed == static_cast<int>(files.size())) {
    throw std::runtime_error(
        fmt::format("none of the {} recordings could be analysed; {} not written", files.size(),
                    path.string()));
  }
  csv::finish(out, path);
  fmt::print("perceive: {} of {} recordings analysed -> {}\n", files.size() - failed, files.size(),
             path.string());
  return failed ? 1 : 0;
}

}  // namespace

void add_perceive(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    std::filesystem::path out_dir;
    int trials = 20;
    std::uint64_t seed = 1;
    int seeds = 1;
    std::filesystem::path recordings;
    bool export_recordings = false;
    int export_trials = 1;
    int threads = 0;
    perception::VariationScale variation;
    std::vector<double> footprints_mm;
    perception::ElectrodeField electrode_field = perception::ElectrodeField::gaussian;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "perceive",
      "Perception evaluation of paper 2 (Ponce Wong et al.): 48 features x 4 exploratory\n"
      "procedures on the simulated fingertip sensor, 76 inputs, SVC for the order of curvature\n"
      "then curvature-specific SVR for the signed footprint (90/10 split per feature).\n"
      "Writes table2.csv, figure7.csv and figure7_<inputs>_exp<k>.svg (and .png), and the\n"
      "classifier's held-out accuracy per footprint (accuracy_by_footprint.csv, _exp<k>.svg and\n"
      ".png). With\n"
      "--recordings DIR, analyses real BioTac-style recordings instead (recordings.csv).\n"
      "With --seeds N, repeats Table 2 on N data sets (seeds SEED..SEED+N-1) and reports each\n"
      "row's spread (table2_seeds.csv): one split holds out only 96 trials.");
  sub->add_option("--out", opt->out_dir, "Folder to write into (created if missing)")->required();
  sub->add_option("--trials", opt->trials, "Trials per feature and procedure (paper: 20)")
      ->check(within(2, 1000));
  sub->add_option("--seed", opt->seed, "Seed of the simulated trials")->check(seed_number());
  auto* seeds = sub->add_option("--seeds", opt->seeds,
                                "Repeat Table 2 on this many data sets, seeds SEED, SEED+1, ...; "
                                "the other files are those of the first")
                    ->check(within(1, 1000));
  add_ranged(*sub, "--threads", opt->threads,
             "Worker threads simulating and analysing trials (0: all cores); the results do "
             "not depend on it",
             0, 256);
  add_ranged(*sub, "--position-variation", opt->variation.position,
             "Scale of the trial-to-trial spread of the feature's position (+-0.1 mm) and of "
             "the contact angle (+-0.1 degree); 0 = none",
             0.0, 100.0);
  add_ranged(*sub, "--depth-variation", opt->variation.depth,
             "Scale of the spread of the commanded depth (3 %); 0 = none", 0.0, 100.0);
  add_ranged(*sub, "--speed-variation", opt->variation.speed,
             "Scale of the spread of the speed (0.5 %); 0 = none", 0.0, 100.0);
  add_mode_option(*sub, "--electrode-field", opt->electrode_field, perception::kElectrodeFieldNames,
                  "How an electrode weighs the skin: gaussian (its face and a 0.4 mm margin) or "
                  "sheet (the fluid as a thin conducting sheet: 1/r^2 out to 3 mm, smooth in the "
                  "position of a small feature)");
  sub->add_option("--footprints", opt->footprints_mm,
                  "Only features of these footprints (mm, of 1.25 2.5 3.75 5 7.5 10 15 20; "
                  "bumps and pits of all three curvatures each), e.g. --footprints 1.25,2.5")
      ->delimiter(',')
      ->check(CLI::IsMember({1.25, 2.5, 3.75, 5.0, 7.5, 10.0, 15.0, 20.0}));
  sub->add_option("--recordings", opt->recordings, "Folder of real *_bio.csv recordings")
      ->check(CLI::ExistingDirectory)
      ->excludes(seeds);
  auto* export_recordings = sub->add_flag(
      "--export-recordings", opt->export_recordings,
      "Also write the first trials of every feature and procedure as BioTac-style CSV, "
      "with labels_<procedure>.csv (file,class,value) for `tactile classify`");
  // Without --export-recordings nothing would be exported: refused rather than ignored.
  sub->add_option("--export-trials", opt->export_trials,
                  "With --export-recordings: how many trials of each (from trial 0)")
      ->check(CLI::Range(1, 1000))
      ->needs(export_recordings)
      ->capture_default_str();
  sub->callback([opt, &action] {
    action = [opt] {
      if (!opt->recordings.empty()) {
        const auto files = recording_files(opt->recordings);
        std::vector<NamedPath> inputs = {{"--recordings", opt->recordings}};
        for (const auto& f : files) inputs.push_back({"--recordings", f});
        refuse_output_over_input({output_folder("--out", opt->out_dir, {"recordings.csv"})},
                                 inputs);
        std::filesystem::create_directories(opt->out_dir);
        return analyse_recordings(files, opt->out_dir);
      }
      refuse_output_over_input({output_folder("--out", opt->out_dir, {})}, {});
      std::filesystem::create_directories(opt->out_dir);
      std::vector<perception::SurfaceFeature> features;
      for (const auto& f : perception::paper_features())
        if (opt->footprints_mm.empty() ||
            std::find(opt->footprints_mm.begin(), opt->footprints_mm.end(), f.footprint_mm) !=
                opt->footprints_mm.end())
          features.push_back(f);
      perception::SensorModel model;
      model.variation = opt->variation;
      model.electrode_field = opt->electrode_field;
      const auto simulate = [&](std::uint64_t seed) {
        const auto t0 = std::chrono::steady_clock::now();
        Progress progress;
        perception::DatasetBuild build;
        build.threads = opt->threads;
        const std::string stage =
            opt->seeds > 1 ? fmt::format("simulating seed {}", seed) : "simulating";
        build.progress = [&](int done, int total) { progress(stage, done, total); };
        auto d = perception::simulate_dataset(opt->trials, seed, model, build, features);
        progress.finish();
        fmt::print(
            "perceive: {} samples ({} features x {} trials, 4 procedures each), {} inputs, "
            "simulated and analysed in {:.1f} s\n",
            d.samples.size(), features.size(), opt->trials, d.names.size(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        return d;
      };
      const auto d = simulate(opt->seed);
      const auto split = perception::split_per_block(d);
      const auto rows = perception::run_table2(d, split);
      fmt::print("Table 2 ({} training / {} held-out samples):\n", split.train.size(),
                 split.test.size());
      for (const auto& row : rows) fmt::print("  {}\n", perception::table2_line(row));
      for (const auto& row : rows)
        if (row.result.inputs == "all")
          fmt::print("  {}\n", perception::misclassified_line(row.result));
      // The tables and their charts replace the old ones together (the exported recordings,
      // hundreds of files, are too many to hold back: they follow).
      CommitTogether together;
      perception::write_table2_csv(opt->out_dir / "table2.csv", rows);
      perception::write_figure7_csv(opt->out_dir / "figure7.csv", rows);
      for (const auto& row : rows)
        perception::write_figure7_chart(
            opt->out_dir /
                fmt::format("figure7_{}_exp{}.svg", row.result.inputs, row.result.degree),
            row.result);
      perception::write_accuracy_by_footprint_csv(opt->out_dir / "accuracy_by_footprint.csv", rows);
      for (int degree : {1, 2})
        perception::write_accuracy_by_footprint_chart(
            opt->out_dir / fmt::format("accuracy_by_footprint_exp{}.svg", degree), rows, degree);
      together.commit();
      if (opt->export_recordings) {
        const auto dir = opt->out_dir / "recordings";
        std::filesystem::create_directories(dir);
        // The first trials of the data set itself (same seeds, same sensor model), with one
        // labels file per procedure (class: curvature, value: signed footprint) for
        // `tactile classify`.
        const int trials = std::min(opt->export_trials, opt->trials);
        for (int p = 0; p < perception::kProcedureCount; ++p) {
          const auto proc = static_cast<perception::Procedure>(p);
          const auto labels_path =
              dir / fmt::format("labels_{}.csv", perception::procedure_short_name(proc));
          auto labels = csv::open_with_header(labels_path, "file,class,value");
          for (const auto& f : features)
            for (int trial = 0; trial < trials; ++trial) {
              const auto name = fmt::format(
                  "{}_{:+g}mm_{}_t{}_bio.csv", kCurvatureNames[static_cast<int>(f.curvature)],
                  f.signed_footprint_mm(), perception::procedure_name(proc), trial);
              perception::write_sensor_csv(
                  dir / name,
                  perception::simulate_trial(
                      f, proc, perception::simulated_trial_seed(f, proc, trial, opt->seed), model));
              labels << fmt::format("{},{},{:g}\n", name,
                                    kCurvatureNames[static_cast<int>(f.curvature)],
                                    f.signed_footprint_mm());
            }
          csv::finish(labels, labels_path);
        }
      }
      fmt::print("perceive: table2.csv, figure7.csv, accuracy_by_footprint.csv and plots -> {}\n",
                 opt->out_dir.string());
      if (opt->seeds == 1) return 0;
      std::vector<perception::SeedTable2> runs{{opt->seed, rows}};
      for (int k = 1; k < opt->seeds; ++k) {
        const std::uint64_t seed = opt->seed + static_cast<std::uint64_t>(k);
        const auto dk = simulate(seed);
        runs.push_back({seed, perception::run_table2(dk, perception::split_per_block(dk))});
        for (const auto& row : runs.back().rows)
          if (row.result.inputs == "all")
            fmt::print("  seed {}: all exp {} {}/{}\n", seed, row.result.degree, row.result.correct,
                       row.result.tested);
      }
      fmt::print("Table 2 over {} seeds ({}-{}), curvature correct on held-out trials:\n",
                 opt->seeds, opt->seed, runs.back().seed);
      for (const auto& line : perception::seed_spread_lines(runs)) fmt::print("  {}\n", line);
      perception::write_table2_seeds_csv(opt->out_dir / "table2_seeds.csv", runs);
      fmt::print("perceive: every seed's Table 2 -> {}\n",
                 (opt->out_dir / "table2_seeds.csv").string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
