#pragma once
// Runs the real `tactile` binary, capturing its exit code and everything it printed.

#include <filesystem>
#include <string>

namespace tactile::test {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `args` is appended to the binary's path as is (the caller quotes what needs quoting).
RunResult run_tactile(const std::string& args);

// The folder the e2e.demo fixture fills (`demo --headless --keep`): frames, calibration, movies.
inline std::filesystem::path demo_dir() {
  return TACTILE_E2E_DEMO_DIR;
}

// A data set vendored under tests/data.
inline std::filesystem::path test_data(const std::string& name) {
  return std::filesystem::path(TACTILE_TEST_DATA_DIR) / name;
}

}  // namespace tactile::test
