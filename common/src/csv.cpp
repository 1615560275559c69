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

bool LineReader::next(std::string& line) {
  if (!std::getline(in_, line)) return false;
  ++number_;
  if (number_ == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

}  // namespace tactile::csv
