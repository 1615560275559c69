// Contact segmentation, windows and Table 1 inputs (see contact_inputs.hpp).

#include "tactile/perception/contact_inputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "tactile/perception/hht.hpp"

namespace tactile::perception {
namespace {

using perception::kElectrodeClusterCount;
using perception::kElectrodeCount;
using perception::Procedure;

constexpr double kVibrationWindowS = 0.25;

double mean(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  double s = 0;
  for (std::size_t i = begin; i < end; ++i) s += v[i];
  return end > begin ? s / static_cast<double>(end - begin) : 0.0;
}

std::size_t baseline_rows(const perception::SensorRecording& r, const ContactOptions& o) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(o.baseline_s * r.rate_hz)));
}

// Mean of v over the baseline rows (0 when there is no baseline to take).
double baseline_of(const std::vector<double>& v, const perception::SensorRecording& r,
                   const ContactOptions& o) {
  const std::size_t n = baseline_rows(r, o);
  switch (o.baseline_at) {
    case ContactOptions::BaselineAt::start:
      return mean(v, 0, n);
    case ContactOptions::BaselineAt::end:
      return mean(v, r.rows() - n, r.rows());
    case ContactOptions::BaselineAt::none:
      break;
  }
  return 0.0;
}

double slope_per_s(const std::vector<double>& v, std::size_t begin, std::size_t end,
                   double rate_hz) {
  if (end < begin + 2) return 0.0;
  const double n = static_cast<double>(end - begin);
  const double t_mean = (n - 1) / 2;
  const double v_mean = mean(v, begin, end);
  double num = 0, den = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const double t = static_cast<double>(i - begin) - t_mean;
    num += t * (v[i] - v_mean);
    den += t * t;
  }
  return num / den * rate_hz;
}

}  // namespace

std::string to_string(ContactOptions::BaselineAt at) {
  return name_in(kBaselineAtNames, at);
}

ContactOptions::BaselineAt parse_baseline_at(std::string_view name) {
  return parse_name("baseline place", name, kBaselineAtNames);
}

std::string to_string(ContactOptions::Electrodes e) {
  return name_in(kElectrodesNames, e);
}

ContactOptions::Electrodes parse_electrodes(std::string_view name) {
  return parse_name("electrode signals", name, kElectrodesNames);
}

void check_trim_fraction(double trim_fraction) {
  if (!(trim_fraction >= 0.0 && trim_fraction < 0.5))
    throw std::invalid_argument(fmt::format(
        "trim fraction {:g} is outside [0, 0.5): it is left out at each end of the contact",
        trim_fraction));
}

std::vector<std::vector<double>> contact_signals(const perception::SensorRecording& r,
                                                 const ContactOptions& o) {
  const bool each = o.electrodes == ContactOptions::Electrodes::each;
  const std::size_t rows = r.rows();
  std::vector<std::vector<double>> s(1 + (each ? kElectrodeCount : kElectrodeClusterCount),
                                     std::vector<double>(rows, 0.0));
  const double p0 = baseline_of(r.pressure, r, o);
  for (std::size_t i = 0; i < rows; ++i) s[0][i] = r.pressure[i] - p0;
  std::array<int, kElectrodeClusterCount> members{};
  for (int e = 0; e < kElectrodeCount; ++e) {
    const int c = each ? e : perception::kElectrodeCluster[e];
    ++members[static_cast<std::size_t>(perception::kElectrodeCluster[e])];
    const double e0 = baseline_of(r.electrodes[e], r, o);
    for (std::size_t i = 0; i < rows; ++i) s[1 + c][i] += r.electrodes[e][i] - e0;
  }
  if (!each)
    for (int c = 0; c < kElectrodeClusterCount; ++c)
      for (double& v : s[1 + c]) v /= members[c];
  return s;
}

std::vector<std::string> contact_signal_names(const ContactOptions& o) {
  const bool each = o.electrodes == ContactOptions::Electrodes::each;
  std::vector<std::string> names = {"pressure"};
  for (int i = 1; i <= (each ? kElectrodeCount : kElectrodeClusterCount); ++i)
    names.push_back(fmt::format("{}{}", each ? 'e' : 'c', i));
  return names;
}

ContactSegment find_contact(const perception::SensorRecording& r, const ContactOptions& o) {
  const auto n_base = static_cast<std::size_t>(std::lround(o.baseline_s * r.rate_hz));
  if (n_base == 0 || r.rows() < n_base + 1 || r.pressure.size() != r.rows())
    throw std::runtime_error(fmt::format("{}: {} rows, too short for a {} s baseline", r.source,
                                         r.rows(), o.baseline_s));
  ContactSegment c;
  c.baseline_pressure = baseline_of(r.pressure, r, o);
  c.threshold = std::max(o.min_threshold, o.threshold_fraction * std::abs(c.baseline_pressure));
  const auto above = [&](std::size_t i) {
    return r.pressure[i] - c.baseline_pressure > c.threshold;
  };
  std::size_t first = 0;
  while (first < r.rows() && !above(first)) ++first;
  if (first == r.rows())
    throw std::runtime_error(
        fmt::format("{}: no contact: pressure never exceeds baseline {:.1f} by {:.2f}", r.source,
                    c.baseline_pressure, c.threshold));
  std::size_t last = r.rows() - 1;
  while (!above(last)) --last;
  c.begin = first;
  c.end = last + 1;
  c.starts_in_contact = first == 0;
  c.ends_in_contact = last + 1 == r.rows();
  return c;
}

namespace {

// The feature contact before trimming.
FeatureContact untrimmed_feature_contact(const perception::SensorRecording& r, Procedure p,
                                         const ContactSegment& c, const ContactOptions& o) {
  if (p == Procedure::static_contact || !o.feature_from_kinematics) return {c.begin, c.end};
  const perception::ProcedureKinematics k = perception::paper_kinematics(p);
  const auto row = [&](double s) {
    return std::clamp(c.begin + static_cast<std::size_t>(std::lround(s * r.rate_hz)), c.begin,
                      c.end);
  };
  if (p == Procedure::roll) return {row(k.approach_s), row(k.approach_s + k.roll_s)};
  // Strokes: from the motion's start to its end (kinematics), narrowed to where the electrode
  // clusters depart from their level at the start of the motion (the flat plate) by more than
  // stroke_activity_fraction of their largest departure.
  const std::size_t move_begin = row(k.approach_s);
  const std::size_t move_end = row(k.approach_s + k.stroke_mm / k.speed_mm_s);
  if (move_end < move_begin + 8) return {c.begin, c.end};
  ContactOptions clusters = o;  // the activity is the clusters' whatever the inputs use
  clusters.electrodes = ContactOptions::Electrodes::clusters;
  const auto s = contact_signals(r, clusters);
  std::vector<double> activity(move_end - move_begin, 0.0);
  double peak = 0;
  for (std::size_t i = move_begin; i < move_end; ++i) {
    double a = 0;
    for (int cl = 1; cl <= kElectrodeClusterCount; ++cl)
      a += std::abs(s[cl][i] - s[cl][move_begin]);
    activity[i - move_begin] = a;
    peak = std::max(peak, a);
  }
  std::size_t first = 0, last = activity.size();
  while (first < activity.size() && activity[first] <= o.stroke_activity_fraction * peak) ++first;
  while (last > first && activity[last - 1] <= o.stroke_activity_fraction * peak) --last;
  if (last < first + 8) return {move_begin, move_end};
  return {move_begin + first, move_begin + last};
}

}  // namespace

FeatureContact find_feature_contact(const perception::SensorRecording& r, Procedure p,
                                    const ContactSegment& c, const ContactOptions& o) {
  check_trim_fraction(o.trim_fraction);
  const FeatureContact f = untrimmed_feature_contact(r, p, c, o);
  if (p == Procedure::static_contact || o.trim_fraction == 0.0) return f;
  const auto cut =
      static_cast<std::size_t>(std::lround(o.trim_fraction * static_cast<double>(f.end - f.begin)));
  return {f.begin + cut, f.end - cut};
}

std::size_t procedure_input_count(Procedure p, const ContactOptions& o) {
  const std::size_t signals = contact_signal_names(o).size();
  return p == Procedure::static_contact ? signals : 3 * signals + 2;
}

std::vector<std::string> procedure_input_names(Procedure p, const ContactOptions& o) {
  const std::string ep = perception::procedure_short_name(p);
  const auto signal_names = contact_signal_names(o);
  std::vector<std::string> names;
  if (p == Procedure::static_contact) {
    for (const auto& s : signal_names) names.push_back(ep + ".mid." + s);
    return names;
  }
  for (const char* w : {"w1", "w2"})
    for (const auto& s : signal_names) names.push_back(fmt::format("{}.{}.{}", ep, w, s));
  for (const auto& s : signal_names) names.push_back(ep + ".rate." + s);
  names.push_back(ep + ".vib.if_first");
  names.push_back(ep + ".vib.if_last");
  return names;
}

std::vector<double> procedure_inputs(const perception::SensorRecording& r, Procedure p,
                                     const ContactOptions& o) {
  const ContactSegment c = find_contact(r, o);
  const auto s = contact_signals(r, o);
  std::vector<double> inputs;
  if (p == Procedure::static_contact) {
    const std::size_t len = c.end - c.begin;
    const std::size_t w0 = c.begin + static_cast<std::size_t>(std::lround(0.35 * len));
    const std::size_t w1 =
        std::max(w0 + 1, c.begin + static_cast<std::size_t>(std::lround(0.65 * len)));
    for (const auto& v : s) inputs.push_back(mean(v, w0, w1));
    return inputs;
  }
  const FeatureContact f = find_feature_contact(r, p, c, o);
  if (f.end < f.begin + 8)
    throw std::runtime_error(fmt::format(
        "{}: feature contact of {} rows is too short for two windows", r.source, f.end - f.begin));
  const std::size_t mid = f.begin + (f.end - f.begin) / 2;
  for (const auto& v : s) inputs.push_back(mean(v, f.begin, mid));
  for (const auto& v : s) inputs.push_back(mean(v, mid, f.end));
  const std::size_t rate_end = f.begin + std::max<std::size_t>(2, (mid - f.begin) / 4);
  for (const auto& v : s) inputs.push_back(slope_per_s(v, f.begin, rate_end, r.rate_hz));

  // Vibration windows: the first and last 250 ms of the feature contact (or all of it when
  // shorter), in vibration samples.
  const double per_row = r.vibration_rate_hz / r.rate_hz;
  const auto v_begin = static_cast<std::size_t>(static_cast<double>(f.begin) * per_row);
  const auto v_end =
      std::min(r.vibration.size(), static_cast<std::size_t>(static_cast<double>(f.end) * per_row));
  const std::size_t v_len =
      std::min(v_end - v_begin, static_cast<std::size_t>(kVibrationWindowS * r.vibration_rate_hz));
  const auto window = [&](std::size_t from) {
    return std::vector<double>(r.vibration.begin() + static_cast<std::ptrdiff_t>(from),
                               r.vibration.begin() + static_cast<std::ptrdiff_t>(from + v_len));
  };
  inputs.push_back(hht::mean_if_first_imf_hz(window(v_begin), r.vibration_rate_hz));
  inputs.push_back(hht::mean_if_first_imf_hz(window(v_end - v_len), r.vibration_rate_hz));
  return inputs;
}

}  // namespace tactile::perception
