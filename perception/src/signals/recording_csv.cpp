// Reading and writing BioTac-style CSV sensor recordings (see recording_csv.hpp).

#include "tactile/perception/recording_csv.hpp"

#include <fmt/format.h>

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
std::vector<std::string> split(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
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
  std::string line;
  if (!std::getline(in, line)) throw FormatError(fmt::format("{}: empty file (no header)", source));
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
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line == "\r") continue;
    const auto fields = split(line);
    if (fields.size() != kFields)
      throw FormatError(fmt::format("{}: line {}: {} fields, expected {} (truncated row?)", source,
                                    line_no, fields.size(), kFields));
    std::vector<double> v(kFields);
    for (std::size_t i = 0; i < kFields; ++i)
      v[i] = parse_number(fields[i], source, line_no, names[i]);
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
