#pragma once
// A whole file as text, for tests that compare what a program wrote.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tactile::test {

inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace tactile::test
