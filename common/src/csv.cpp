#include "tactile/common/csv.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace tactile::csv {

std::ofstream open_with_header(const std::filesystem::path& path, const std::string& header) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  out << header << '\n';
  return out;
}

void finish(std::ofstream& out, const std::filesystem::path& path) {
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("writing {} failed (disk full?)", path.string()));
  out.close();
}

}  // namespace tactile::csv
