#include "csv_rows.hpp"

#include <fstream>
#include <sstream>

namespace tactile::test {

std::vector<std::vector<std::string>> read_csv_rows(const std::filesystem::path& path,
                                                    bool skip_comment) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (skip_comment && line.starts_with("#")) continue;
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

}  // namespace tactile::test
