#include "scene_options.hpp"

#include <fmt/format.h>

#include <set>
#include <system_error>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::cli {

void refuse_stale_frames(const std::string& option, const std::filesystem::path& dir,
                         int frame_count) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return;
  std::set<std::string> written;
  for (int f = 0; f < frame_count; ++f) {
    written.insert(capture::frame_file_name(static_cast<std::size_t>(f)));
  }
  std::vector<std::string> stale;
  try {
    for (const auto& p : capture::list_frames(dir)) {
      if (!written.contains(p.filename().string())) stale.push_back(p.filename().string());
    }
  } catch (const FormatError&) {
    return;  // no image at all
  }
  if (stale.empty()) return;
  throw OutputPathError(fmt::format(
      "{} {} already holds {} image file(s) this run of {} frames would not replace ({}{}): "
      "`tactile capture` would read them as part of the sequence; remove them or choose another "
      "folder",
      option, dir.string(), stale.size(), frame_count, stale.front(),
      stale.size() > 1 ? fmt::format(" .. {}", stale.back()) : std::string()));
}

}  // namespace tactile::cli
