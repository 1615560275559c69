// synth(out_dir, ...): a synthetic sequence with exact ground truth, or a real print moved by an
// exact warp (from_print=...), written by the run `tactile synth` makes (capture::run_synth),
// its keywords made from the synth request's option table; returns what was written.

#include <string>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/capture/synth_request.hpp"

namespace tactile::python {

namespace {

py::dict synth(const std::filesystem::path& out_dir, const py::kwargs& kwargs) {
  capture::SynthRequest request;
  request.out_dir = out_dir;
  set_from_kwargs(request, capture::synth_options(), kwargs, "synth");
  const capture::ResolvedSynth run = capture::resolve(request, OptionSpelling::python);
  capture::SynthSummary s;
  {
    py::gil_scoped_release unlocked;
    s = with_inputs({run.print, run.marks.value_or(std::filesystem::path{})},
                    [&] { return capture::run_synth(run, "python: tactile.synth"); });
  }
  using S = capture::SynthSummary;
  py::dict d;
  put_fields(d, s, field("frames", &S::frames), field("width_px", &S::width_px),
             field("height_px", &S::height_px), field("landmark_positions", &S::landmark_positions),
             field("marked_pores", &S::marked_pores), field("seconds", &S::seconds),
             field("summary", &S::text));
  return d;
}

}  // namespace

void bind_synth(py::module_& m) {
  def_with_kwargs(
      m, "synth", &synth, capture::synth_options(),
      "Writes a synthetic fingerprint sequence with exact ground truth into out_dir, as `tactile\n"
      "synth`: frame_NNN.png, landmarks.csv and scene.json (and calibration/dot_grid.png for a\n"
      "scene); with from_print, a real print moved by an exact warp. Returns frames, width_px,\n"
      "height_px, landmark_positions, marked_pores, seconds and the summary line. Keywords\n"
      "(the command line's options, with underscores):",
      py::arg("out_dir"));
}

}  // namespace tactile::python
