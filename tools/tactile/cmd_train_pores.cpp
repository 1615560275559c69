// `tactile train-pores`: retrain the ridge-blob pore model on a researcher's own hand-marked
// prints, write it as a model file, and say how well it finds the marked pores.

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/capture/pore_score.hpp"
#include "tactile/capture/pore_training.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

void print_score_row(const std::string& name, const capture::PoreScore& s) {
  fmt::print("  {:<16} {:>6.3f} {:>6.3f} {:>8} {:>7} {:>9}\n", name, s.true_detection_rate(),
             s.false_detection_rate(), s.matched, s.marked, s.detected);
}

// models[i] scores print i; prints the table and returns the overall score.
capture::PoreScore print_score_table(const std::string& title,
                                     const std::vector<capture::PoreTrainingPrint>& prints,
                                     const std::vector<const std::vector<double>*>& models,
                                     const capture::PoreTrainingSettings& settings) {
  fmt::print("{}\n  {:<16} {:>6} {:>6} {:>8} {:>7} {:>9}\n", title, "print", "TDR", "FDR",
             "matched", "marked", "detected");
  capture::PoreScore total;
  for (std::size_t i = 0; i < prints.size(); ++i) {
    capture::RidgeBlobParams params = settings.params;
    params.model = *models[i];
    const capture::PoreScore s =
        capture::score_ridge_blob_pores(prints[i], settings.px_per_mm, params);
    print_score_row(prints[i].name, s);
    total += s;
  }
  print_score_row("overall", total);
  return total;
}

}  // namespace

void add_train_pores(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path prints_dir;
    double px_per_mm = 0;
    fs::path out;
    double label_radius_mm = capture::PoreTrainingSettings{}.label_radius_mm;
    double l2 = capture::PoreTrainingSettings{}.l2;
    bool held_out = false;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "train-pores",
      "Train the ridge-blob pore model (--pores ridge-blob) on your own hand-marked prints and\n"
      "write it as a model file for --pore-model.\n"
      "The --prints folder holds pairs image_NN.<jpg|png|bmp|tif> + pores_NN.txt (the PolyU\n"
      "HRF layout). A marks file has one marked pore per line, `row col`, 1-based pixel\n"
      "coordinates separated by white space, e.g.\n"
      "    42 17\n"
      "    86 120\n"
      "Mark every pore of the image: unmarked pores teach the model that they are not pores.\n"
      "Prints a table of TDR (marked pores found), FDR (detections that are no marked pore),\n"
      "matched / marked / detected per print, pairing detections and marks one-to-one as\n"
      "mutual nearest neighbours within 0.15 mm; --held-out also scores each print with a\n"
      "model trained on the other prints, which says whether the model generalises.");
  sub->add_option("--prints", opt->prints_dir, "Folder of marked prints")
      ->type_name("DIR")
      ->required();
  sub->add_option("--px-per-mm", opt->px_per_mm,
                  "Scale of the prints, pixels per millimetre (PolyU HRF: 47)")
      ->required()
      ->check(within(2.0, 5000.0));
  sub->add_option("--out", opt->out, "Model file to write (JSON)")
      ->type_name("MODEL.json")
      ->required();
  add_ranged(*sub, "--label-radius-mm", opt->label_radius_mm,
             "A candidate this close to a marked pore counts as a pore", 0.01, 1.0);
  add_ranged(*sub, "--l2", opt->l2, "L2 penalty on every coefficient but the intercept", 0.0,
             1000000.0);
  sub->add_flag("--held-out", opt->held_out,
                "Also score each print with a model trained on the others (leave one print out)");
  sub->callback([opt, &action] {
    action = [opt] {
      const auto t0 = std::chrono::steady_clock::now();
      // Checked first: training takes seconds to minutes, and its result would be lost.
      const fs::path out_dir = opt->out.parent_path();
      if (!out_dir.empty() && !fs::is_directory(out_dir)) {
        throw std::runtime_error(
            fmt::format("{}: no such folder for --out {}", out_dir.string(), opt->out.string()));
      }
      std::vector<NamedPath> inputs = {{"--prints", opt->prints_dir}};
      for (const auto& file : capture::pore_training_files(opt->prints_dir))
        inputs.push_back({"--prints", file});
      refuse_output_over_input({output_file("--out", opt->out)}, inputs);
      const auto prints = capture::read_pore_training_prints(opt->prints_dir);
      std::size_t marked = 0;
      for (const auto& p : prints) marked += p.pores_px.size();
      fmt::print("train-pores: {} prints, {} marked pores in {}\n", prints.size(), marked,
                 opt->prints_dir.string());
      capture::PoreTrainingSettings settings;
      settings.px_per_mm = opt->px_per_mm;
      settings.label_radius_mm = opt->label_radius_mm;
      settings.l2 = opt->l2;
      const auto models =
          capture::train_pore_models(prints, settings, opt->held_out, [&](int k, int n) {
            std::fflush(stdout);  // results on stdout, progress on stderr: keep a log in order
            fmt::print(stderr, "train-pores: labelling print {} of {} ({})\n", k, n,
                       prints[static_cast<std::size_t>(k - 1)].name);
          });
      capture::PoreModelFile file;
      file.coefficients = models.model;
      file.px_per_mm = settings.px_per_mm;
      file.label_radius_mm = settings.label_radius_mm;
      file.l2 = settings.l2;
      file.min_log_odds = settings.params.min_log_odds;
      for (const auto& p : prints) file.trained_on.push_back(p.name);
      capture::write_pore_model_json(opt->out, file);
      fmt::print("train-pores: wrote {} ({} coefficients, threshold log-odds {})\n",
                 opt->out.string(), file.coefficients.size(), file.min_log_odds);

      const std::vector<const std::vector<double>*> trained(prints.size(), &models.model);
      print_score_table("trained model on its training prints:", prints, trained, settings);
      if (opt->held_out) {
        std::vector<const std::vector<double>*> held_out;
        for (const auto& m : models.held_out) held_out.push_back(&m);
        print_score_table("held out (each print scored by a model trained on the others):", prints,
                          held_out, settings);
      }
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print("train-pores: {:.1f} s\n", s);
      return 0;
    };
  });
}

}  // namespace tactile::cli
