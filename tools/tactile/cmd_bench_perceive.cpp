// `tactile bench perceive`: training and testing every model of one Table 2 (5 input sets x 2
// kernels, each an SVC and 3 SVRs: 40 models) with our libsvm models; target <= 1 s. WEKA's
// SMO/SMOreg are timed on the same ARFF sets in the same run (their reported build times and
// the wall time of the java processes).

#include <fmt/format.h>

#include <unistd.h>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/perception/arff.hpp"
#include "tactile/perception/report.hpp"

namespace tactile::cli {
namespace {

// Runs one WEKA classifier; returns its reported "Time taken to build model" (s).
double run_weka(const std::string& java, const std::string& jar, const std::string& classifier,
                const std::filesystem::path& train, const std::filesystem::path& test) {
  const std::string command = fmt::format("{} -cp {} {} -t {} -T {} -o 2>&1", java, jar, classifier,
                                          train.string(), test.string());
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe.get())) out += buffer.data();
  // WEKA prints "Time taken to build model: 0.12 seconds".
  const std::string marker = "Time taken to build model: ";
  const auto at = out.find(marker);
  if (at == std::string::npos) {
    throw std::runtime_error("WEKA did not report a build time:\n" + out);
  }
  try {
    return std::stod(out.substr(at + marker.size()));
  } catch (const std::exception&) {
    throw std::runtime_error("WEKA's build time is not a number:\n" + out);
  }
}

}  // namespace

void add_bench_perceive(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    int trials = 20;
    std::string java = "java";
    std::string weka_jar = "/usr/share/java/weka.jar";
    bool no_weka = false;
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "perceive",
      "Time training + testing every model of one Table 2 (paper 2) on the simulated sensor:\n"
      "target <= 1 s; WEKA's SMO and SMOreg timed on the same data in the same run.");
  add_ranged(*sub, "--trials", opt->trials, "Trials per feature (paper: 20)", 2, 1000);
  sub->add_option("--java", opt->java, "Java launcher")->capture_default_str();
  sub->add_option("--weka-jar", opt->weka_jar, "weka.jar")->capture_default_str();
  sub->add_flag("--no-weka", opt->no_weka, "Skip the WEKA timing");
  sub->callback([opt, &action] {
    action = [opt] {
      auto t0 = std::chrono::steady_clock::now();
      perception::DatasetBuild build;
      build.threads = 0;  // all cores: the data set is the same, and its making is not timed
      const auto d = perception::simulate_dataset(opt->trials, 1, {}, build);
      const auto split = perception::split_per_block(d);
      fmt::print(
          "bench perceive: {} samples simulated and analysed in {:.1f} s (not timed below)\n",
          d.samples.size(), seconds_since(t0));
      t0 = std::chrono::steady_clock::now();
      const auto rows = perception::run_table2(d, split);
      const double ours_s = seconds_since(t0);
      double summed_s = 0;
      for (const auto& row : rows) summed_s += row.train_test_s;
      fmt::print(
          "ours (libsvm): {} rows x (1 SVC + 3 SVR) trained and tested in {:.3f} s on {} threads, "
          "{:.3f} s of model time summed over rows (target <= 1 s: {})\n",
          rows.size(), ours_s, std::max(1u, std::thread::hardware_concurrency()), summed_s,
          ours_s <= 1.0 ? "met" : "NOT met");
      if (opt->no_weka) return 0;
      if (!std::filesystem::exists(opt->weka_jar)) {
        fmt::print("WEKA: {} not found, not timed\n", opt->weka_jar);
        return 0;
      }
      const auto dir = std::filesystem::temp_directory_path() /
                       fmt::format("tactile_bench_perceive_{}", ::getpid());
      std::filesystem::create_directories(dir);
      double built_s = 0;
      int runs = 0;
      t0 = std::chrono::steady_clock::now();
      for (const auto& set : perception::table2_input_sets(d))
        for (int degree : {1, 2}) {
          const std::string kernel = fmt::format(
              "-K \"weka.classifiers.functions.supportVector.PolyKernel -C 250007 -E {}.0\"",
              degree);
          perception::write_arff(dir / "train.arff", d, split.train, set.columns,
                                 perception::ArffTarget::curvature);
          perception::write_arff(dir / "test.arff", d, split.test, set.columns,
                                 perception::ArffTarget::curvature);
          built_s += run_weka(opt->java, opt->weka_jar,
                              "weka.classifiers.functions.SMO -C 1.0 -L 0.001 -P 1.0E-12 -N 0 "
                              "-V -1 -W 1 " +
                                  kernel,
                              dir / "train.arff", dir / "test.arff");
          ++runs;
          for (int c = 0; c < 3; ++c) {
            std::vector<std::size_t> train, test;
            for (auto i : split.train)
              if (d.samples[i].curvature == c) train.push_back(i);
            for (auto i : split.test)
              if (d.samples[i].curvature == c) test.push_back(i);
            perception::write_arff(dir / "train.arff", d, train, set.columns,
                                   perception::ArffTarget::footprint);
            perception::write_arff(dir / "test.arff", d, test, set.columns,
                                   perception::ArffTarget::footprint);
            built_s += run_weka(opt->java, opt->weka_jar,
                                "weka.classifiers.functions.SMOreg -C 1.0 -N 0 " + kernel,
                                dir / "train.arff", dir / "test.arff");
            ++runs;
          }
        }
      const double weka_wall_s = seconds_since(t0);
      std::filesystem::remove_all(dir);
      fmt::print(
          "WEKA (SMO/SMOreg): {} models, reported build time {:.3f} s; {:.1f} s wall "
          "including {} JVM starts, ARFF writing and evaluation\n",
          runs, built_s, weka_wall_s, runs);
      fmt::print("ours / WEKA build time: {:.2f}\n", built_s > 0 ? ours_s / built_s : 0.0);
      return 0;
    };
  });
}

}  // namespace tactile::cli
