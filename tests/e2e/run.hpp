#pragma once
// Runs the real `tactile` binary, capturing its exit code and everything it printed.

#include <string>

namespace tactile::test {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `args` is appended to the binary's path as is (the caller quotes what needs quoting).
RunResult run_tactile(const std::string& args);

}  // namespace tactile::test
