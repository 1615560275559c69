#include "json_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

#include "tactile/common/error.hpp"

namespace tactile::capture {

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".partial";
  {
    std::ofstream out(tmp);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw std::runtime_error(fmt::format("cannot write {}", path.string()));
    }
  }
  std::filesystem::rename(tmp, path);
}

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

}  // namespace tactile::capture
