#include "tactile/common/atomic_write.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace tactile {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& partial)>& write) {
  const std::filesystem::path partial = path.string() + ".partial";
  try {
    write(partial);
    std::filesystem::rename(partial, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& partial) {
    std::ofstream out(partial);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  });
}

}  // namespace tactile
