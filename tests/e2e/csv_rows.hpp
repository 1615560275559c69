#pragma once
// Reads back a CSV file that the binary wrote, for the end-to-end tests' checks.

#include <filesystem>
#include <string>
#include <vector>

namespace tactile::test {

// Every line of `path` split at commas (the project's CSV exports quote nothing), the header
// included; with `skip_comment`, lines starting with '#' are left out.
std::vector<std::vector<std::string>> read_csv_rows(const std::filesystem::path& path,
                                                    bool skip_comment = false);

}  // namespace tactile::test
