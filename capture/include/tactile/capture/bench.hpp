#pragma once
// The capture benchmarks: the strain measurement (landmark pipeline and the Lucas-Kanade and DIS
// baselines, same strain computation) run on sequences with exact ground truth, timed and
// scored, and pushed one condition at a time until it fails. Two kinds of sequence: the
// synthetic scenes (`tactile bench capture`) and real hand-marked prints moved by exact warps
// (`tactile bench prints`), whose tuning and held-out prints are kept apart. The command line
// only parses options and prints what these return; every figure is computed here.

#include <functional>
#include <string>
#include <vector>

#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/pore_training.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::capture {

// Where a stability sweep first fails: accuracy and yield fail at different points, and each is
// reported on its own.
struct SweepFailures {
  double accuracy_at = -1;  // first value whose strain error was too large; -1 = none yet
  double yield_at = -1;     // first value with too few tracked landmarks; -1 = none yet

  void note(double value, bool accurate, bool enough);
  bool both_failed() const { return accuracy_at >= 0 && yield_at >= 0; }
  // "  -> NAME: strain error fails at V; landmark yield holds up to LAST"
  std::string summary(const std::string& name, double last_value) const;
};

// The edge strain RMS error the measurement is held to on the synthetic scenes, and on real
// prints under exact warps (bench prints and bench live): one value each, so that the goals the
// charts draw and the limits the sweeps fail at cannot drift apart.
inline constexpr double kSceneStrainTarget = 0.005;
inline constexpr double kPrintStrainTarget = 0.0025;

// A sweep point fails when the strain error exceeds max_rms (or no edge was measured) or the
// median tracked landmarks per frame fall below min_points.
struct SweepLimits {
  double max_rms = kSceneStrainTarget;
  double min_points = 100;
};
// Where each bench's sweeps fail unless told otherwise (--max-rms, --min-points).
inline constexpr SweepLimits kSceneSweepLimits{.max_rms = kSceneStrainTarget, .min_points = 100};
inline constexpr SweepLimits kPrintSweepLimits{.max_rms = kPrintStrainTarget, .min_points = 150};

// ---------------------------------------------------------------- synthetic scenes

using SequenceMethod = std::function<StrainMovie(const std::vector<GrayImage>& frames,
                                                 const Calibration& calibration, double rate_hz)>;

struct SceneBenchMethod {
  std::string name;
  SequenceMethod run;
};

// The default pipeline with 2 and 1 threads, then (unless quick) with the optimal assignment
// and with minutiae, then Lucas-Kanade and DIS. The first is the default pipeline.
std::vector<SceneBenchMethod> scene_bench_methods(bool quick);

struct SceneBenchResult {
  std::string method;
  Scene scene = Scene::bump;
  int frames = 0;
  double seconds = 0;
  double cpu_seconds = 0;  // every thread of the process: the machine may be shared
  Evaluation eval;
  std::string error;  // a method that throws is a failure, not a crash of the benchmark

  double frames_per_s() const { return seconds > 0 ? frames / seconds : 0.0; }
  double cpu_ms_per_frame() const { return frames > 0 ? 1e3 * cpu_seconds / frames : 0.0; }
};

// Times the method on the sequence (rendering excluded) and scores it against its truth.
SceneBenchResult run_scene_bench(const SceneBenchMethod& method, const SyntheticSequence& sequence);

// Every scene of kScenes with frame_count frames, through every method in order;
// on_result sees each result as soon as it is measured.
std::vector<SceneBenchResult> bench_scenes(
    int frame_count, const std::vector<SceneBenchMethod>& methods,
    const std::function<void(const SceneBenchResult&)>& on_result);

struct SceneSweep {
  std::string name;
  std::vector<double> values;  // from easy to hard
  std::function<void(SceneSpec&, double)> apply;
};

// Noise, blur, contrast, speed, pore size, loss of contact and patch size, each on the bump.
std::vector<SceneSweep> scene_sweeps();

struct SceneSweepPoint {
  double value = 0;
  SceneBenchResult result;  // scene "bump"
  bool accurate = false;
  bool enough = false;
};

// The sweep's values in order on a bump of frame_count frames, until both accuracy and yield
// have failed; on_point sees each point as soon as it is measured.
SweepFailures run_scene_sweep(const SceneSweep& sweep, const SceneBenchMethod& method,
                              int frame_count, const SweepLimits& limits,
                              const std::function<void(const SceneSweepPoint&)>& on_point);

// ---------------------------------------------------------------- real prints

struct PrintBenchMethod {
  std::string name;
  std::function<StrainMovie(const PrintSequence&)> run;
};

// "landmarks (default)" (the settings `tactile capture` picks given only the scale),
// "Lucas-Kanade" and "DIS flow"; tracks may be as short as the sequence.
std::vector<PrintBenchMethod> print_bench_methods();

// One warp of the bench: travel_mm_per_s > 0 makes it the fast scene (set_fast_scene).
struct PrintBenchCase {
  WarpPattern pattern = WarpPattern::wave;
  double strain = 0.04;
  double travel_mm_per_s = 0;
  double contact_loss = 0;  // PrintWarpSpec::contact_loss
};

// Quick: the 4 % wave and the fast 8 % wave; else rigid, stretch, compress and bump at 4 %, the
// wave at 1, 4 and 8 % and the fast 8 % wave.
std::vector<PrintBenchCase> print_bench_cases(bool quick);

// The other motions of the speed of touch, each as the fast scene at 8 %: a bump (pulse) and
// a ridge of compression crossing at 25 mm/s, stick-slip, random displacement kernels, and the
// fast wave with a region that lifts off and lands again.
std::vector<PrintBenchCase> touch_bench_cases();

// Full slip at 4 % (the skin sliding through the view under a static field) at 10, 25, 50 and
// 100 mm/s, 60 Hz; travel_mm_per_s is the skin's speed. Lucas-Kanade then re-seeds every frame
// and keeps tracks as short as the capture does.
std::vector<PrintBenchCase> slip_bench_cases();

// "wave", "wave-fast" for a case with a travel speed, "slip-S" for full slip at S mm/s, "+loss"
// added for a loss of contact.
std::string case_label(const PrintBenchCase& c);

// The fast scene: the pattern crossing at travel_mm_per_s, filmed as a camera does (a 2 ms
// exposure, each pixel integrated over its area), the finger sliding at 2.5 mm/s and turning
// 3 degrees.
void set_fast_scene(PrintWarpSpec& spec, double travel_mm_per_s);

// The bench's spec for a print: its size and scale, frame_count frames, everything else default.
PrintWarpSpec print_bench_spec(const PoreTrainingPrint& print, double px_per_mm, int frame_count);

// "07" of "image_07.jpg".
std::string print_number(const std::string& file_name);

struct PrintBenchRow {
  std::string print;  // print_number
  bool held_out = false;
  std::string pattern;  // case_label
  double strain = 0;
  std::string method;
  double frames_per_s = 0;
  double cpu_ms_per_frame = 0;  // every thread's CPU time: the machine may be shared
  Evaluation eval;
};

// Times the method on the sequence and scores it (print, group, pattern and strain left empty).
PrintBenchRow run_print_bench(const PrintBenchMethod& method, const PrintSequence& sequence);

struct PrintBenchOptions {
  std::vector<std::string> held_out;  // print numbers kept out of tuning
  int frame_count = 30;
  double px_per_mm = 47;
  std::vector<PrintBenchCase> cases;
  std::size_t method_count = 3;  // the first this many of `methods`
};

// The print mirrored about its edges (as its mirror image, the next copy as itself, and so on)
// until it fills width_px x height_px, its marks mirrored with it: real ridge and pore texture
// over a camera's whole frame when the prints are smaller than the frame. Throws
// std::invalid_argument for a size outside 1 to 10000 px.
PoreTrainingPrint mirrored_to_size(const PoreTrainingPrint& print, int width_px, int height_px);

// Every print x case x method, in that order; on_row sees each row as soon as it is measured.
std::vector<PrintBenchRow> bench_prints(const std::vector<PoreTrainingPrint>& prints,
                                        const std::vector<PrintBenchMethod>& methods,
                                        const PrintBenchOptions& options,
                                        const std::function<void(const PrintBenchRow&)>& on_row);

// Medians over one method's sequences of one group; correlation over the non-rigid ones.
struct PrintBenchSummary {
  std::string method;
  bool held_out = false;
  double points = 0;
  double rms_error = 0;
  double correlation = 0;
  double min_correlation = 0;
  double frames_per_s = 0;
  double cpu_ms_per_frame = 0;
};

// Per method (in the order given), tuning then held-out; groups without rows are left out.
std::vector<PrintBenchSummary> summarise_print_bench(const std::vector<PrintBenchRow>& rows,
                                                     const std::vector<std::string>& method_names);

struct PrintSweep {
  std::string name;
  std::vector<double> values;  // from easy to hard
  std::function<void(PrintWarpSpec&, double)> apply;
  bool every_method = false;  // the pipeline, Lucas-Kanade and DIS, each to its failure
};

// Noise, blur, strain, slide (the pipeline alone), exploration speed at 60 Hz and camera rate at
// 25 mm/s (every method; the fast 8 % wave), and full-slip speed at 60 Hz and camera rate at
// 50 mm/s (every method; the 4 % field of `--slip`).
std::vector<PrintSweep> print_sweeps();

struct PrintSweepPoint {
  double value = 0;
  PrintBenchRow row;
  bool accurate = false;
  bool enough = false;
};

// The sweep's values in order on the print (without its marks), until both accuracy and yield
// have failed; on_point sees each point as soon as it is measured.
SweepFailures run_print_sweep(const PrintSweep& sweep, const PrintBenchMethod& method,
                              const PoreTrainingPrint& print, const PrintBenchOptions& options,
                              const SweepLimits& limits,
                              const std::function<void(const PrintSweepPoint&)>& on_point);

}  // namespace tactile::capture
