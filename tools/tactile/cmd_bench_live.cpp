// `tactile bench live`: the live session's latency and drops against frame size and camera
// rate, and its strain's accuracy against the truth and against the batch capture of the same
// frames (live::bench_live), printed, as CSV and as a chart of latency against accuracy.

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_files.hpp"
#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/option_table.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/live/bench_live.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_bench_live(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path prints;
    std::string print = "12";
    bool quick = false;
    std::vector<std::string> cases;
    fs::path out = "bench-live";
    live::LiveBenchOptions bench;
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "live",
      "The live session on a real print: the print (image_NN + pores_NN.txt of PRINTS_DIR, e.g.\n"
      "tests/data/polyu-hrf-pores; print 12 is held out of the capture's tuning) mirrored to\n"
      "320 x 240 and 640 x 484 px and moved by an 8 % wave crossing at the speed of touch, held\n"
      "in memory and handed to the session at 30, 60, 120 and 240 Hz as a camera would, into the\n"
      "emulated display. Prints frames in, processed, dropped, latency p50/p99/max and the live\n"
      "strain's error and correlation against the truth beside the batch capture's on the same\n"
      "frames; writes OUT/bench_live.csv and OUT/latency_accuracy_live.png (and .svg).");
  add_input_folder(*sub, "PRINTS_DIR", opt->prints, "Folder of marked prints");
  sub->add_option("--print", opt->print, "Number NN of the print to use")->capture_default_str();
  add_ranged(*sub, "--seconds", opt->bench.seconds, "Seconds of skin per case", 0.5, 600.0);
  add_ranged(*sub, "--travel", opt->bench.travel_mm_per_s,
             "Speed of the wave across the contact (mm/s)", 1.0, 500.0);
  auto* quick = sub->add_flag("--quick", opt->quick,
                              "Only 320 x 240 at 60 and 120 Hz and 640 x 484 at 60 Hz");
  sub->add_option("--case", opt->cases,
                  "Only this case, WIDTHxHEIGHT@RATE (e.g. 640x484@60; repeat for more)")
      ->excludes(quick);
  sub->add_option("--out", opt->out, "Folder for the CSV and the chart")->capture_default_str();
  sub->callback([opt, &action] {
    action = [opt] {
      refuse_output_over_input({output_folder("--out", opt->out,
                                              {"bench_live.csv", "latency_accuracy_live.png",
                                               "latency_accuracy_live.svg"})},
                               {{"PRINTS_DIR", opt->prints}});
      const auto prints = capture::read_pore_training_prints(opt->prints);
      const auto print = std::find_if(prints.begin(), prints.end(), [&](const auto& p) {
        return capture::print_number(p.name) == opt->print;
      });
      if (print == prints.end()) {
        throw RequestError(fmt::format("--print {}: {} holds no print image_{}.*", opt->print,
                                       opt->prints.string(), opt->print));
      }
      if (opt->cases.empty()) {
        opt->bench.cases = live::live_bench_cases(opt->quick);
      } else {
        opt->bench.cases.clear();
        for (const auto& c : opt->cases) {
          try {
            opt->bench.cases.push_back(live::parse_live_bench_case(c));
          } catch (const std::invalid_argument& e) {
            throw RequestError(fmt::format("--case: {}", e.what()));
          }
        }
      }
      fs::create_directories(opt->out);
      fmt::print(
          "{} ({:g} s of skin a case, 8 % wave at {:g} mm/s; latency: frame available -> "
          "its first device frame sent)\n",
          print->name, opt->bench.seconds, opt->bench.travel_mm_per_s);
      fmt::print("{}", live::live_bench_table_header());
      const auto rows = live::bench_live(*print, opt->bench, [](const live::LiveBenchRow& r) {
        fmt::print("{}", live::live_bench_table_row(r));
        std::fflush(stdout);
      });
      write_bench_files("bench live", opt->out / "bench_live.csv", live::live_bench_csv_header(),
                        rows, live::live_bench_csv_row, opt->out / "latency_accuracy_live.png",
                        live::live_bench_chart(rows));
      return 0;
    };
  });
}

}  // namespace tactile::cli
