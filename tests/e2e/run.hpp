#pragma once
// Runs the real `tactile` binary, capturing its exit code and everything it printed.

#include <filesystem>
#include <string>
#include <vector>

namespace tactile::test {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `args` is appended to the binary's path as is (the caller quotes what needs quoting).
RunResult run_tactile(const std::string& args);

// The real `tactile` binary started without a shell (a shell's background job ignores SIGINT),
// its stdout and stderr going to `log`, so that a test can signal it mid-run.
class Started {
 public:
  // `environment`: NAME=VALUE entries set for it on top of this process's environment.
  Started(const std::vector<std::string>& args, const std::filesystem::path& log,
          const std::vector<std::string>& environment = {});
  ~Started();  // kills and reaps a process still running (a failed test)
  Started(const Started&) = delete;
  Started& operator=(const Started&) = delete;

  int pid() const { return pid_; }
  void signal(int sig) const;
  // Waits at most `limit_s` until the process watches `sig` on a signal descriptor (a
  // StopSignals, found in /proc/PID/fdinfo), i.e. until it has set up its own stop handling: a
  // signal sent before that ends it by the default action, which is not what a stop test means
  // to try. (Its mask is no sign: `tactile` blocks the stop signals from before main().)
  bool wait_until_watching(int sig, double limit_s) const;
  struct Ended {
    bool ended = false;  // false: still running when the wait gave up
    int exit_code = -1;  // when it exited
    int killed_by = 0;   // the signal that ended it instead (not the same as exiting 128 + it)
  };
  // Waits at most `limit_s` for the process to end.
  Ended wait(double limit_s);

 private:
  int pid_ = -1;
};

// The folder the e2e.demo fixture fills (`demo --headless --keep`): frames, calibration, movies.
inline std::filesystem::path demo_dir() {
  return TACTILE_E2E_DEMO_DIR;
}

// A data set vendored under tests/data.
inline std::filesystem::path test_data(const std::string& name) {
  return std::filesystem::path(TACTILE_TEST_DATA_DIR) / name;
}

}  // namespace tactile::test
