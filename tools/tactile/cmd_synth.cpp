// `tactile synth`: render a synthetic fingertip sequence with exact ground truth. The options,
// their rules and the run are the synth request's (capture/synth_request.hpp).

#include <fmt/format.h>

#include <memory>
#include <string>

#include "command.hpp"
#include "number_checks.hpp"
#include "progress.hpp"
#include "request_options.hpp"
#include "tactile/capture/synth_request.hpp"

namespace tactile::cli {

void add_synth(CLI::App& app, Action& action, const std::string& command_line) {
  const auto [request, sub] = add_request_command<capture::SynthRequest>(
      app, "synth",
      "Render a synthetic prism (FTIR) fingerprint sequence with exact ground truth.\n"
      "Writes frame_NNN.png, calibration/dot_grid.png (0.5 mm grid through the same camera),\n"
      "landmarks.csv (true position of every landmark in every frame) and scene.json.\n"
      "With --from-print IMAGE: a real print moved by a known smooth warp (slide, rotation and a\n"
      "strain pattern) and filmed with blur, noise and a brightness drift, so that `tactile\n"
      "evaluate` scores a capture of real skin against the exact warp.",
      capture::synth_options());
  // The old spelling of --rate-hz, hidden from --help and kept for scripts written against it
  // (a hidden option has no name in CLI11's messages, so its rules are checked below).
  const auto* rate_row = find_option(capture::synth_options(), "rate_hz");
  sub->add_option_function<double>(
         "--rate",
         [request, rate_row](double rate_hz) {
           fmt::print(stderr, "tactile synth: warning: --rate is deprecated; use --rate-hz\n");
           set_option(*request, *rate_row, rate_hz, OptionSpelling::cli);
         },
         "")
      ->check(within(1.0, 100000.0))
      ->group("");
  sub->callback([request, &action, sub, &command_line] {
    if (sub->count("--rate") > 0 && sub->count("--rate-hz") > 0) {
      throw CLI::ExcludesError("--rate", "--rate-hz");
    }
    if (sub->count("--rate") > 0 && !request->from_print) {
      throw CLI::RequiresError("--rate", "--from-print");
    }
    const capture::ResolvedSynth synth = capture::resolve(*request, OptionSpelling::cli);
    action = [synth, &command_line] {
      Progress progress;
      const capture::SynthSummary s = capture::run_synth(
          synth, command_line, [&](int done, int total) { progress("render", done, total); });
      progress.finish();
      fmt::print("{}\n", s.text);
      return 0;
    };
  });
}

}  // namespace tactile::cli
