#pragma once
// Signal analysis of paper 2: baseline, contact segmentation, the per-procedure windows and
// the inputs of Table 1, from a BioTac-style recording (real or simulated).
//
// Inputs per exploratory procedure (our reading of Table 1; 7 + 3 x 23 = 76):
// - static contact: the means of pressure and of the 6 electrode clusters over the middle 30 %
//   of the contact (7); the window is steady by construction, so no rates or vibration;
// - each of the distal-proximal stroke, radial-ulnar stroke and roll: the 7 means over each
//   half of the feature contact (14), the 7 initial rates of change (least-squares slope over
//   the first 25 % of the first window, per second) (7), and the mean instantaneous frequency
//   of the first IMF of the vibration over the first and the last 250 ms of the feature
//   contact (2).
// Pressure and electrodes are taken relative to their baselines.
//
// Options for real slides, none of them the paper's (defaults leave the paper's inputs as
// above): each of the 19 electrodes instead of the 6 cluster means, no baseline (signals as
// recorded, for files the recording software already tared), and a trimmed feature contact.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/common/names.hpp"
#include "tactile/perception/recording.hpp"
#include "tactile/perception/sensor_scene.hpp"

namespace tactile::perception {

// Options of the signal analysis: baseline, contact, feature contact, and which signals.
struct ContactOptions {
  // Where the free-air baseline is: at the start (the paper: before contact), at the end
  // (recordings that begin in contact, like tests/data/biotac-slide), or nowhere: the recording
  // software already subtracted one, so the signals are taken as recorded (baseline 0).
  enum class BaselineAt { start, end, none } baseline_at = BaselineAt::start;
  double baseline_s = 0.2;            // duration averaged for the baseline
  double threshold_fraction = 0.002;  // contact: pressure above baseline by 0.2 % of baseline
  double min_threshold = 1.0;         // counts; for baselines near 0 (baseline-subtracted files)
  // Feature contact from the procedure's kinematics (the paper's scenes); false: the whole
  // contact is the feature contact (recordings of uniform textures, unknown kinematics).
  bool feature_from_kinematics = true;
  double stroke_activity_fraction = 0.1;  // strokes: feature contact where activity exceeds this
  // Strokes and roll: leave out this fraction of the feature contact at each end, in [0, 0.5)
  // (on a slide the first and last parts are the press and the lift, not the texture).
  double trim_fraction = 0.0;
  // The electrode signals: the paper's 6 cluster means, or each of the 19 electrodes.
  enum class Electrodes { clusters, each } electrodes = Electrodes::clusters;
};

inline constexpr std::array<Named<ContactOptions::BaselineAt>, 3> kBaselineAtNames = {{
    {ContactOptions::BaselineAt::start, "start"},
    {ContactOptions::BaselineAt::end, "end"},
    {ContactOptions::BaselineAt::none, "none"},
}};
inline constexpr std::array<Named<ContactOptions::Electrodes>, 2> kElectrodesNames = {{
    {ContactOptions::Electrodes::clusters, "clusters"},
    {ContactOptions::Electrodes::each, "each"},
}};
// Names of `classify train --baseline-at` / `--electrodes` and of model files; the parsers
// throw std::invalid_argument naming the bad name and the accepted ones.
std::string to_string(ContactOptions::BaselineAt at);
ContactOptions::BaselineAt parse_baseline_at(std::string_view name);
std::string to_string(ContactOptions::Electrodes e);
ContactOptions::Electrodes parse_electrodes(std::string_view name);
// Throws std::invalid_argument naming a trim fraction outside [0, 0.5).
void check_trim_fraction(double trim_fraction);

// Pressure then the electrode signals (clusters or each electrode), relative to the baseline,
// one value per row: the signals the window means and rates are taken of.
std::vector<std::vector<double>> contact_signals(const perception::SensorRecording& r,
                                                 const ContactOptions& o = {});
// Their names ("pressure", "c1".."c6" or "e1".."e19").
std::vector<std::string> contact_signal_names(const ContactOptions& o = {});

struct ContactSegment {
  std::size_t begin = 0, end = 0;  // rows [begin, end) in contact
  double baseline_pressure = 0;
  double threshold = 0;            // pressure rise that counts as contact
  bool starts_in_contact = false;  // the first row is already above threshold
  bool ends_in_contact = false;
};

// Throws std::runtime_error naming the recording when there is no contact at all or the
// recording is shorter than the baseline.
ContactSegment find_contact(const perception::SensorRecording& r, const ContactOptions& o = {});

// Rows [begin, end) of contact with the feature, by procedure: static contact, the whole
// contact; strokes, within the motion (contact onset + press ramp + stroke length / speed, from
// perception::paper_kinematics), where the electrode clusters' total departure from their level at
// the motion's start exceeds stroke_activity_fraction of its peak; roll, the roll itself
// (contact without the press and release ramps).
struct FeatureContact {
  std::size_t begin = 0, end = 0;
};
FeatureContact find_feature_contact(const perception::SensorRecording& r, perception::Procedure p,
                                    const ContactSegment& contact, const ContactOptions& o = {});

// The procedure's inputs (7 or 23 with the paper's clusters; 20 or 62 with each electrode) and
// their names (e.g. "dp.w1.pressure", "dp.rate.c3", "dp.w2.e17", "roll.vib.if_last").
std::vector<double> procedure_inputs(const perception::SensorRecording& r, perception::Procedure p,
                                     const ContactOptions& o = {});
std::vector<std::string> procedure_input_names(perception::Procedure p,
                                               const ContactOptions& o = {});
std::size_t procedure_input_count(perception::Procedure p, const ContactOptions& o = {});

}  // namespace tactile::perception
