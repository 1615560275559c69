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
// whole contact in 7 octave bands, 10-1100 Hz, 7) and "stds" (standard deviation of pressure
// and of each electrode signal over the feature contact, 7 or 20). "stats", the plain summary
// statistics a reviewer would compare the paper's inputs with: mean and standard deviation of
// pressure and of each electrode signal over the feature contact, the vibration's standard
// deviation and the 7 band powers (14 + 1 + 7 = 22, or 40 + 1 + 7 = 48 with each electrode);
// it holds "bands" and "stds", so it is not combined with them. Static contact has "means" (7)
// and "stats". With `contact.electrodes` each, the 6 clusters become the 19 electrodes in every
// group (means 40, rates 20, stds 20).

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "tactile/common/names.hpp"
#include "tactile/perception/contact_inputs.hpp"
#include "tactile/perception/recording.hpp"

namespace tactile::perception {

enum class InputGroup { means, rates, hht, bands, stds, stats };
inline constexpr std::array<Named<InputGroup>, 6> kInputGroupNames = {{
    {InputGroup::means, "means"},
    {InputGroup::rates, "rates"},
    {InputGroup::hht, "hht"},
    {InputGroup::bands, "bands"},
    {InputGroup::stds, "stds"},
    {InputGroup::stats, "stats"},
}};
inline constexpr auto kInputGroups = values_of(kInputGroupNames);
// The names of model files and of `classify train --inputs`. The parser throws
// std::invalid_argument naming the bad name and the accepted ones.
std::string to_string(InputGroup group);
InputGroup parse_input_group(std::string_view name);

struct RecordingInputOptions {
  Procedure procedure = Procedure::distal_proximal;
  std::vector<InputGroup> groups = {InputGroup::means, InputGroup::rates, InputGroup::hht};
  // Real slides begin in contact (tests/data/biotac-materials), so the free-air baseline is at
  // the end; the kinematics of the paper's scenes are unknown, so all contact is feature.
  ContactOptions contact = [] {
    ContactOptions o;
    o.baseline_at = ContactOptions::BaselineAt::end;
    o.feature_from_kinematics = false;
    return o;
  }();
};

// What a recording is: a slide over a texture ("stroke": distal-proximal inputs, all contact is
// feature contact), a press ("static"), or one of the paper's scenes "dp", "ru", "roll" (feature
// contact from the paper's kinematics, as the 76 inputs of Table 2). The names are those of
// `classify train --procedure` and of model files.
enum class RecordingProcedure { stroke, static_contact, distal_proximal, radial_ulnar, roll };
inline constexpr std::array<Named<RecordingProcedure>, 5> kRecordingProcedureNames = {{
    {RecordingProcedure::stroke, "stroke"},
    {RecordingProcedure::static_contact, "static"},
    {RecordingProcedure::distal_proximal, "dp"},
    {RecordingProcedure::radial_ulnar, "ru"},
    {RecordingProcedure::roll, "roll"},
}};
std::string to_string(RecordingProcedure procedure);
// Throws std::invalid_argument naming the bad name and the accepted ones.
RecordingProcedure parse_recording_procedure(std::string_view name);

// Sets `o.procedure` and `o.contact.feature_from_kinematics` for what the recording is.
void set_recording_procedure(RecordingInputOptions& o, RecordingProcedure procedure);
RecordingProcedure recording_procedure(const RecordingInputOptions& o);

// The inputs `classify train --procedure NAME` uses unless told otherwise. The paper's scenes
// (dp, ru, roll, static): the paper's groups, clusters, no trim, baseline at the end. Real slides
// ("stroke"): what `classify train --select` chooses on 200 real slides of 20 materials
// (model_selection.hpp, docs/perception-models.md): groups means and bands, the 6 clusters, no
// baseline (the files are tared by the recording software, and many end still in contact, so
// their last 0.2 s is no baseline), 20 % trimmed at each end.
RecordingInputOptions default_recording_inputs(RecordingProcedure procedure);

// The groups a procedure has (all for strokes; means and stats for static).
std::vector<InputGroup> recording_input_groups(Procedure p);

// Names of the selected inputs, in order (e.g. "dp.w1.pressure", "dp.vib.if_first",
// "dp.band.10_20hz"). Throws std::invalid_argument for a group the procedure does not have.
std::vector<std::string> recording_input_names(const RecordingInputOptions& o);

// The selected inputs of one recording. Throws std::runtime_error naming the recording when it
// has no contact or its contact is too short for the windows.
std::vector<double> recording_inputs(const SensorRecording& r, const RecordingInputOptions& o);

// The inputs of each of `o.groups` apart, in the order given and without checking that the
// groups go together, so that one analysis serves several sets of groups (model selection):
// recording_inputs concatenates them in the fixed order. Throws as recording_inputs.
std::vector<std::vector<double>> recording_inputs_by_group(const SensorRecording& r,
                                                           const RecordingInputOptions& o);

// Input groups in the fixed order of the model's inputs (recording_input_groups), checked: none
// the procedure lacks, none twice over (stats with bands or stds), at least one. Throws
// std::invalid_argument naming the group.
std::vector<InputGroup> selected_groups(const RecordingInputOptions& o);

}  // namespace tactile::perception
