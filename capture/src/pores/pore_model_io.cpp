#include "tactile/capture/pore_model_io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "pores/pore_model.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"

namespace tactile::capture {

namespace {

constexpr const char* kFormat = "tactile-pore-model";
constexpr int kFormatVersion = 1;

double finite_field(const nlohmann::json& j, const char* name, const std::string& where) {
  const double v = json_field<double>(j, name, where);
  if (!std::isfinite(v)) throw FormatError(fmt::format("{}: '{}' is not finite", where, name));
  return v;
}

}  // namespace

void write_pore_model_json(const std::filesystem::path& path, const PoreModelFile& model) {
  check_pore_model(model.coefficients);
  for (double w : model.coefficients) {
    // JSON has no NaN or infinity: such a model could not be read back.
    if (!std::isfinite(w)) throw std::invalid_argument("pore model has a non-finite coefficient");
  }
  nlohmann::ordered_json j;  // in this order, so the file reads top-down
  j["format"] = kFormat;
  j["format_version"] = kFormatVersion;
  j["measures"] = kPoreMeasures;
  j["coefficient_count"] = model.coefficients.size();
  j["px_per_mm"] = model.px_per_mm;
  j["label_radius_mm"] = model.label_radius_mm;
  j["l2"] = model.l2;
  j["min_log_odds"] = model.min_log_odds;
  j["trained_on"] = model.trained_on;
  j["coefficients"] = model.coefficients;
  write_text_atomically(path, j.dump(2) + '\n');
}

PoreModelFile read_pore_model_json(const std::filesystem::path& path) {
  const std::string where = path.string();
  const nlohmann::json j = read_json_of_format(path, "pore model file", kFormat);
  const int version = json_field<int>(j, "format_version", where);
  if (version != kFormatVersion) {
    throw FormatError(fmt::format("{}: format_version {} is not supported (this program reads {})",
                                  where, version, kFormatVersion));
  }
  const int measures = json_field<int>(j, "measures", where);
  if (measures != static_cast<int>(kPoreMeasures)) {
    throw FormatError(
        fmt::format("{}: the model weighs {} measures, this program's pore detector has {}", where,
                    measures, kPoreMeasures));
  }
  PoreModelFile m;
  const auto& coefficients = j.contains("coefficients") ? j.at("coefficients") : nlohmann::json();
  if (!coefficients.is_array()) {
    throw FormatError(fmt::format("{}: field 'coefficients' is {}", where,
                                  coefficients.is_null() ? "missing" : "not an array"));
  }
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    if (!coefficients[i].is_number()) {
      throw FormatError(fmt::format("{}: coefficient {} is not a number", where, i));
    }
    m.coefficients.push_back(coefficients[i].get<double>());
    if (!std::isfinite(m.coefficients.back())) {
      throw FormatError(fmt::format("{}: coefficient {} is not finite", where, i));
    }
  }
  // A model is only meaningful for the detector whose measures it weighs.
  try {
    check_pore_model(m.coefficients);
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", where, e.what()));
  }
  const int count = json_field<int>(j, "coefficient_count", where);
  if (count != static_cast<int>(m.coefficients.size())) {
    throw FormatError(fmt::format("{}: 'coefficient_count' is {} but 'coefficients' holds {}",
                                  where, count, m.coefficients.size()));
  }
  m.px_per_mm = finite_field(j, "px_per_mm", where);
  m.label_radius_mm = finite_field(j, "label_radius_mm", where);
  m.l2 = finite_field(j, "l2", where);
  m.min_log_odds = finite_field(j, "min_log_odds", where);
  m.trained_on = json_field<std::vector<std::string>>(j, "trained_on", where);
  if (!(m.px_per_mm > 0)) {
    throw FormatError(fmt::format("{}: 'px_per_mm' must be positive", where));
  }
  if (!(m.label_radius_mm > 0)) {
    throw FormatError(fmt::format("{}: 'label_radius_mm' must be positive", where));
  }
  if (m.l2 < 0) throw FormatError(fmt::format("{}: 'l2' must not be negative", where));
  return m;
}

}  // namespace tactile::capture
