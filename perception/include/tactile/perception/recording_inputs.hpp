#pragma once
// Inputs of one real recording for a classifier, through the same code as the 76 inputs of
// Table 1 (procedure_inputs): a recording is analysed as one exploratory procedure (a slide over
// a texture is a stroke; a press without motion is static contact), and the inputs are chosen
// by group so that what carries the class can be measured group by group.
//
// Groups of a stroke (23 inputs, the paper's): "means" (pressure and 6 electrode clusters over
// each half of the contact, 14), "rates" (their initial rates of change, 7), "hht" (mean
// instantaneous frequency of the first IMF of the vibration over the first and last 250 ms, 2).
// Not the paper's, for comparison with the HHT: "bands" (log10 power of the vibration over the
// whole contact in 7 octave bands, 10-1100 Hz, 7). Static contact has only "means" (7).

#include <string>
#include <vector>

#include "tactile/perception/features.hpp"
#include "tactile/perception/recording.hpp"

namespace tactile::perception {

struct RecordingInputOptions {
  Procedure procedure = Procedure::distal_proximal;
  std::vector<std::string> groups = {"means", "rates", "hht"};
  // Real slides begin in contact (tests/data/biotac-materials), so the free-air baseline is at
  // the end; the kinematics of the paper's scenes are unknown, so all contact is feature.
  ContactOptions contact = [] {
    ContactOptions o;
    o.baseline_at = ContactOptions::BaselineAt::end;
    o.feature_from_kinematics = false;
    return o;
  }();
};

// What a recording is, by name: "stroke" (a slide over a texture: distal-proximal inputs, all
// contact is feature contact), "static" (a press), or one of the paper's scenes "dp", "ru",
// "roll" (feature contact from the paper's kinematics, as the 76 inputs of Table 2). Sets
// `o.procedure` and `o.contact.feature_from_kinematics`; throws std::invalid_argument naming the
// word for any other.
void set_recording_procedure(RecordingInputOptions& o, const std::string& name);
std::string recording_procedure_name(const RecordingInputOptions& o);

// The groups a procedure has ("means", "rates", "hht", "bands" for strokes; "means" for static).
std::vector<std::string> recording_input_groups(Procedure p);

// Names of the selected inputs, in order (e.g. "dp.w1.pressure", "dp.vib.if_first",
// "dp.band.10_20hz"). Throws std::invalid_argument for a group the procedure does not have.
std::vector<std::string> recording_input_names(const RecordingInputOptions& o);

// The selected inputs of one recording. Throws std::runtime_error naming the recording when it
// has no contact or its contact is too short for the windows.
std::vector<double> recording_inputs(const SensorRecording& r, const RecordingInputOptions& o);

}  // namespace tactile::perception
