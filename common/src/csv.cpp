#include "tactile/common/csv.hpp"

namespace tactile::csv {

AtomicOstream open_with_header(const std::filesystem::path& path, const std::string& header) {
  AtomicOstream out(path);
  out << header << '\n';
  return out;
}

void finish(AtomicOstream& out, const std::filesystem::path& /*path*/) {
  out.commit();
}

}  // namespace tactile::csv
