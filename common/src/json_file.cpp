#include "tactile/common/json_file.hpp"

#include <fmt/format.h>

#include <fstream>

#include "tactile/common/error.hpp"

namespace tactile {

nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what) {
  const std::string where = path.string();
  std::ifstream in(path);
  if (!in) throw FormatError(fmt::format("{}: cannot open {}", where, what));
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers beyond a double
    throw FormatError(fmt::format("{}: not valid JSON ({})", where, e.what()));
  }
  if (!j.is_object()) throw FormatError(fmt::format("{}: expected a JSON object", where));
  return j;
}

}  // namespace tactile
