#pragma once
// The one temporary folder of the tests: created fresh, unique, and removed when the object goes
// away. ctest runs each test in its own process, several at once (-j), and the same test of two
// build trees may run at the same time, so a folder named only after its test would be shared;
// mkdtemp makes the name unique and creates the folder in one step. The test's name stays in the
// folder's name so that a kept folder (TACTILE_KEEP_TEST_DIRS=1, for looking at what a failing
// test wrote) says whose it is.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace tactile::test {

class TempDir {
 public:
  // `label` tells apart several folders of one test.
  explicit TempDir(std::string_view label = {}) {
    // Appended piece by piece: GCC 12 at -O3 warns falsely (-Wrestrict) on "-" + std::string.
    std::string name = "tactile";
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
      name += '-';
      name += info->test_suite_name();
      name += '.';
      name += info->name();
    }
    if (!label.empty()) {
      name += '-';
      name += label;
    }
    for (char& c : name)
      if (c == '/' || c == ' ') c = '_';  // parameterised tests' names hold '/'
    name += "-XXXXXX";
    std::string pattern = (std::filesystem::temp_directory_path() / name).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::system_error(errno, std::generic_category(), pattern);
    }
    path_ = pattern;
  }
  ~TempDir() {
    if (const char* keep = std::getenv("TACTILE_KEEP_TEST_DIRS");
        keep && std::string(keep) == "1") {
      std::fprintf(stderr, "kept test folder %s\n", path_.c_str());
      return;
    }
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& p) const { return path_ / p; }

 private:
  std::filesystem::path path_;
};

}  // namespace tactile::test
