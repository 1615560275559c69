// Reading and writing BioTac-style CSV sensor recordings (see recording_csv.hpp).

#include "tactile/perception/recording_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"

namespace tactile::perception {
namespace {

constexpr std::size_t kFields = 4 + kVibrationPerRow + kElectrodeCount;  // 45

std::vector<std::string> expected_header() {
  std::vector<std::string> names = {"timestamp", "tdc", "tac", "pdc"};
  for (int i = 1; i <= kVibrationPerRow; ++i) names.push_back(fmt::format("pac{}", i));
  for (int i = 1; i <= kElectrodeCount; ++i) names.push_back(fmt::format("ele{}", i));
  return names;
}

// Splits on commas; one empty trailing field (the recordings' trailing comma) is dropped.
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

// The BioTac's converters give 12-bit counts (0..4095), stored raw or with a baseline taken
// off; a simulated sensor is not clipped at the converter's end. Far beyond both, a value is
// damage or a unit mix-up, never a measurement.
constexpr double kMaxCounts = 100000;

bool constant(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
}

// Every row the same but for its time: pressure, each of a row's 22 vibration samples (a row
// repeated is one 10 ms pattern repeated, no vibration) and every electrode.
bool every_signal_constant(const SensorRecording& r) {
  for (std::size_t i = kVibrationPerRow; i < r.vibration.size(); ++i)
    if (r.vibration[i] != r.vibration[i - kVibrationPerRow]) return false;
  return constant(r.pressure) &&
         std::all_of(r.electrodes.begin(), r.electrodes.end(),
                     [](const std::vector<double>& e) { return constant(e); });
}

double parse_number(const std::string& field, const std::string& source, std::size_t line,
                    const std::string& column) {
  double value = 0;
  const char* begin = field.data();
  const char* end = begin + field.size();
  while (begin < end && *begin == ' ') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || begin == end || !std::isfinite(value))
    throw FormatError(
        fmt::format("{}: line {}: column '{}': '{}' is not a number", source, line, column, field));
  return value;
}

}  // namespace

SensorRecording read_sensor_csv(std::istream& in, const std::string& source) {
  const auto names = expected_header();
  csv::LineReader lines(in);
  std::string line;
  if (!lines.next(line)) throw FormatError(fmt::format("{}: empty file (no header)", source));
  const auto header = split(line);
  if (header.size() != kFields)
    throw FormatError(fmt::format("{}: line 1: header has {} columns, expected {} ({}..{})", source,
                                  header.size(), kFields, names.front(), names.back()));
  for (std::size_t i = 0; i < kFields; ++i)
    if (header[i] != names[i])
      throw FormatError(fmt::format("{}: line 1: column {} is '{}', expected '{}'", source, i + 1,
                                    header[i], names[i]));
  SensorRecording r;
  r.source = source;
  while (lines.next(line)) {
    const std::size_t line_no = lines.number();
    if (line.empty()) continue;
    const auto fields = split(line);
    if (fields.size() != kFields)
      throw FormatError(fmt::format("{}: line {}: {} fields, expected {} (truncated row?)", source,
                                    line_no, fields.size(), kFields));
    std::vector<double> v(kFields);
    for (std::size_t i = 0; i < kFields; ++i) {
      v[i] = parse_number(fields[i], source, line_no, names[i]);
      if (i > 0 && std::abs(v[i]) > kMaxCounts)
        throw FormatError(fmt::format(
            "{}: line {}: column '{}': {} is out of range: a sensor's counts lie within -{} to {}",
            source, line_no, names[i], fields[i], kMaxCounts, kMaxCounts));
    }
    if (!r.t_s.empty() && v[0] < r.t_s.back())
      throw FormatError(
          fmt::format("{}: line {}: timestamp {} goes back in time", source, line_no, fields[0]));
    r.t_s.push_back(v[0]);
    r.temperature_dc.push_back(v[1]);
    r.temperature_ac.push_back(v[2]);
    r.pressure.push_back(v[3]);
    for (int k = 0; k < kVibrationPerRow; ++k) r.vibration.push_back(v[4 + k]);
    for (int e = 0; e < kElectrodeCount; ++e)
      r.electrodes[e].push_back(v[4 + kVibrationPerRow + e]);
  }
  if (r.t_s.empty()) throw FormatError(fmt::format("{}: no data rows after the header", source));
  if (r.rows() > 1 && every_signal_constant(r))
    throw FormatError(fmt::format(
        "{}: pressure, vibration and all {} electrodes hold one value each over all {} rows: the "
        "sensor measured nothing (unplugged, or its values were not written)",
        source, kElectrodeCount, r.rows()));
  return r;
}

SensorRecording read_sensor_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open for reading", path.string()));
  return read_sensor_csv(in, path.string());
}

void write_sensor_csv(const std::filesystem::path& path, const SensorRecording& r) {
  std::string header;
  for (const auto& name : expected_header()) header += (header.empty() ? "" : ",") + name;
  auto out = csv::open_with_header(path, header);
  for (std::size_t i = 0; i < r.rows(); ++i) {
    out << fmt::format("{:.6f},{:g},{:g},{:.3f}", r.t_s[i], r.temperature_dc[i],
                       r.temperature_ac[i], r.pressure[i]);
    for (int k = 0; k < kVibrationPerRow; ++k)
      out << fmt::format(",{:.3f}", r.vibration[i * kVibrationPerRow + k]);
    for (int e = 0; e < kElectrodeCount; ++e) out << fmt::format(",{:.3f}", r.electrodes[e][i]);
    out << '\n';
  }
  csv::finish(out, path);
}

}  // namespace tactile::perception
