// Inputs of one real recording by group (see recording_inputs.hpp).

#include "tactile/perception/recording_inputs.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <utility>

#include "tactile/perception/hht.hpp"

namespace tactile::perception {
namespace {

// Octave bands of the vibration up to its Nyquist frequency (1100 Hz at 2200 Hz).
constexpr std::array<double, 8> kBandEdgesHz = {10, 20, 40, 80, 160, 320, 640, 1100};

bool is_static(Procedure p) {
  return p == Procedure::static_contact;
}

// Groups the procedure has; with `whole`, also a set of groups a model can take: at least one,
// none held twice over.
void check_groups(const RecordingInputOptions& o, bool whole) {
  const auto known = recording_input_groups(o.procedure);
  for (const auto& g : o.groups)
    if (std::find(known.begin(), known.end(), g) == known.end())
      throw std::invalid_argument(fmt::format("input group '{}' does not apply to {} (has: {})",
                                              to_string(g), to_string(recording_procedure(o)),
                                              fmt::join(names_of(known), ", ")));
  if (!whole) return;
  if (o.groups.empty()) throw std::invalid_argument("no input groups selected");
  const auto has = [&](InputGroup g) {
    return std::find(o.groups.begin(), o.groups.end(), g) != o.groups.end();
  };
  for (const auto g : {InputGroup::bands, InputGroup::stds})
    if (has(InputGroup::stats) && has(g))
      throw std::invalid_argument(
          fmt::format("input group '{}' is part of 'stats': select one of them", to_string(g)));
}

// Mean power per band of the mean-removed vibration, log10 (plus 1 so silence gives 0).
std::vector<double> band_powers(const SensorRecording& r, std::size_t row_begin,
                                std::size_t row_end) {
  const double per_row = r.vibration_rate_hz / r.rate_hz;
  const auto v_begin = static_cast<std::size_t>(static_cast<double>(row_begin) * per_row);
  const auto v_end = std::min(r.vibration.size(),
                              static_cast<std::size_t>(static_cast<double>(row_end) * per_row));
  std::vector<std::complex<double>> x;
  double m = 0;
  for (std::size_t i = v_begin; i < v_end; ++i) m += r.vibration[i];
  m /= std::max<double>(1.0, static_cast<double>(v_end - v_begin));
  for (std::size_t i = v_begin; i < v_end; ++i) x.emplace_back(r.vibration[i] - m, 0.0);
  std::vector<double> out(kBandEdgesHz.size() - 1, 0.0);
  if (x.size() < 2) return out;
  const auto spectrum = hht::fft(x);
  const double n = static_cast<double>(x.size());
  std::vector<int> bins(out.size(), 0);
  for (std::size_t k = 1; k < x.size() / 2 + 1; ++k) {
    const double f_hz = static_cast<double>(k) * r.vibration_rate_hz / n;
    for (std::size_t b = 0; b < out.size(); ++b)
      if (f_hz >= kBandEdgesHz[b] && f_hz < kBandEdgesHz[b + 1]) {
        out[b] += std::norm(spectrum[k]) / (n * n);
        ++bins[b];
      }
  }
  for (std::size_t b = 0; b < out.size(); ++b)
    out[b] = std::log10(1.0 + (bins[b] ? out[b] / bins[b] : 0.0));
  return out;
}

// Mean and standard deviation (population) of v over [begin, end).
std::pair<double, double> mean_and_std(const std::vector<double>& v, std::size_t begin,
                                       std::size_t end) {
  const double n = static_cast<double>(std::max<std::size_t>(1, end - begin));
  double m = 0, ss = 0;
  for (std::size_t i = begin; i < end; ++i) m += v[i];
  m /= n;
  for (std::size_t i = begin; i < end; ++i) ss += (v[i] - m) * (v[i] - m);
  return {m, std::sqrt(ss / n)};
}

// Standard deviation of each signal over rows [begin, end): how much it varies over the slide,
// which the window means do not see.
std::vector<double> signal_stds(const SensorRecording& r, const ContactOptions& o,
                                std::size_t begin, std::size_t end) {
  std::vector<double> out;
  for (const auto& v : contact_signals(r, o)) out.push_back(mean_and_std(v, begin, end).second);
  return out;
}

// Mean and standard deviation (population) of each signal over rows [begin, end), then the
// vibration's standard deviation over the same rows.
std::vector<double> signal_stats(const SensorRecording& r, const ContactOptions& o,
                                 std::size_t begin, std::size_t end) {
  std::vector<double> out;
  for (const auto& v : contact_signals(r, o)) {
    const auto [m, sd] = mean_and_std(v, begin, end);
    out.push_back(m);
    out.push_back(sd);
  }
  const double per_row = r.vibration_rate_hz / r.rate_hz;
  const auto v_end =
      std::min(r.vibration.size(), static_cast<std::size_t>(static_cast<double>(end) * per_row));
  const auto v_begin =
      std::min(v_end, static_cast<std::size_t>(static_cast<double>(begin) * per_row));
  // The vibration is AC-coupled: its mean carries nothing.
  out.push_back(mean_and_std(r.vibration, v_begin, v_end).second);
  return out;
}

}  // namespace

std::string to_string(InputGroup group) {
  return name_in(kInputGroupNames, group);
}

InputGroup parse_input_group(std::string_view name) {
  return parse_name("input group", name, kInputGroupNames);
}

std::string to_string(RecordingProcedure procedure) {
  return name_in(kRecordingProcedureNames, procedure);
}

RecordingProcedure parse_recording_procedure(std::string_view name) {
  return parse_name("procedure", name, kRecordingProcedureNames);
}

void set_recording_procedure(RecordingInputOptions& o, RecordingProcedure procedure) {
  switch (procedure) {
    case RecordingProcedure::static_contact:
      o.procedure = Procedure::static_contact;
      break;
    case RecordingProcedure::stroke:  // a slide: the distal-proximal inputs
    case RecordingProcedure::distal_proximal:
      o.procedure = Procedure::distal_proximal;
      break;
    case RecordingProcedure::radial_ulnar:
      o.procedure = Procedure::radial_ulnar;
      break;
    case RecordingProcedure::roll:
      o.procedure = Procedure::roll;
      break;
  }
  // A stroke's and a press's kinematics are unknown: all their contact is feature contact.
  o.contact.feature_from_kinematics =
      procedure != RecordingProcedure::stroke && procedure != RecordingProcedure::static_contact;
}

RecordingProcedure recording_procedure(const RecordingInputOptions& o) {
  if (is_static(o.procedure)) return RecordingProcedure::static_contact;
  if (!o.contact.feature_from_kinematics) return RecordingProcedure::stroke;
  switch (o.procedure) {
    case Procedure::radial_ulnar:
      return RecordingProcedure::radial_ulnar;
    case Procedure::roll:
      return RecordingProcedure::roll;
    default:
      return RecordingProcedure::distal_proximal;
  }
}

RecordingInputOptions default_recording_inputs(RecordingProcedure procedure) {
  RecordingInputOptions o;
  set_recording_procedure(o, procedure);
  if (is_static(o.procedure)) {
    o.groups = {InputGroup::means};
  } else if (!o.contact.feature_from_kinematics) {
    o.groups = {InputGroup::means, InputGroup::bands};
    o.contact.baseline_at = ContactOptions::BaselineAt::none;
    o.contact.electrodes = ContactOptions::Electrodes::clusters;
    o.contact.trim_fraction = 0.2;
  }
  return o;
}

std::vector<InputGroup> recording_input_groups(Procedure p) {
  if (is_static(p)) return {InputGroup::means, InputGroup::stats};
  return {kInputGroups.begin(), kInputGroups.end()};
}

namespace {

// Columns [first, second) of procedure_inputs that a group takes (bands, stds and stats take
// none: they are computed apart).
std::pair<std::size_t, std::size_t> group_columns(const RecordingInputOptions& o,
                                                  InputGroup group) {
  const std::size_t n = contact_signal_names(o.contact).size();
  switch (group) {
    case InputGroup::means:
      return {0, is_static(o.procedure) ? n : 2 * n};
    case InputGroup::rates:
      return {2 * n, 3 * n};
    case InputGroup::hht:
      return {3 * n, 3 * n + 2};
    case InputGroup::bands:
    case InputGroup::stds:
    case InputGroup::stats:
      break;
  }
  return {0, 0};
}

template <typename T>
void append_group(std::vector<T>& out, const std::vector<T>& all, const RecordingInputOptions& o,
                  InputGroup group) {
  const auto [first, last] = group_columns(o, group);
  out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(first),
             all.begin() + static_cast<std::ptrdiff_t>(last));
}

}  // namespace

std::vector<InputGroup> selected_groups(const RecordingInputOptions& o) {
  check_groups(o, true);
  std::vector<InputGroup> selected;
  for (const auto& g : recording_input_groups(o.procedure))
    if (std::find(o.groups.begin(), o.groups.end(), g) != o.groups.end()) selected.push_back(g);
  return selected;
}

std::vector<std::string> recording_input_names(const RecordingInputOptions& o) {
  const auto all = procedure_input_names(o.procedure, o.contact);
  const std::string ep = procedure_short_name(o.procedure);
  std::vector<std::string> names;
  for (const auto g : selected_groups(o)) {
    append_group(names, all, o, g);
    if (g == InputGroup::stats) {
      for (const auto& s : contact_signal_names(o.contact)) {
        names.push_back(ep + ".mean." + s);
        names.push_back(ep + ".std." + s);
      }
      names.push_back(ep + ".std.vibration");
    }
    if (g == InputGroup::bands || g == InputGroup::stats)
      for (std::size_t b = 0; b + 1 < kBandEdgesHz.size(); ++b)
        names.push_back(
            fmt::format("{}.band.{:g}_{:g}hz", ep, kBandEdgesHz[b], kBandEdgesHz[b + 1]));
    if (g == InputGroup::stds)
      for (const auto& s : contact_signal_names(o.contact)) names.push_back(ep + ".std." + s);
  }
  return names;
}

std::vector<std::vector<double>> recording_inputs_by_group(const SensorRecording& r,
                                                           const RecordingInputOptions& o) {
  check_groups(o, false);
  const auto has = [&](InputGroup g) {
    return std::find(o.groups.begin(), o.groups.end(), g) != o.groups.end();
  };
  // The procedure's inputs (the HHT among them) are the costly part: only when a group uses them.
  std::vector<double> all;
  if (has(InputGroup::means) || has(InputGroup::rates) || has(InputGroup::hht))
    all = procedure_inputs(r, o.procedure, o.contact);
  FeatureContact f;
  std::vector<double> bands;  // once, for bands and stats
  if (has(InputGroup::bands) || has(InputGroup::stds) || has(InputGroup::stats))
    f = find_feature_contact(r, o.procedure, find_contact(r, o.contact), o.contact);
  if (has(InputGroup::bands) || has(InputGroup::stats)) bands = band_powers(r, f.begin, f.end);
  std::vector<std::vector<double>> out;
  for (const auto g : o.groups) {
    auto& inputs = out.emplace_back();
    append_group(inputs, all, o, g);
    if (g == InputGroup::stats) inputs = signal_stats(r, o.contact, f.begin, f.end);
    if (g == InputGroup::bands || g == InputGroup::stats)
      inputs.insert(inputs.end(), bands.begin(), bands.end());
    if (g == InputGroup::stds) inputs = signal_stds(r, o.contact, f.begin, f.end);
  }
  return out;
}

std::vector<double> recording_inputs(const SensorRecording& r, const RecordingInputOptions& o) {
  auto selected = o;
  selected.groups = selected_groups(o);
  std::vector<double> inputs;
  for (const auto& group : recording_inputs_by_group(r, selected))
    inputs.insert(inputs.end(), group.begin(), group.end());
  return inputs;
}

}  // namespace tactile::perception
