#include "run.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include <array>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace tactile::test {

RunResult run_tactile(const std::string& args) {
  const std::string cmd = std::string(TACTILE_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot start " + cmd);
  RunResult r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

Started::Started(const std::vector<std::string>& args, const std::filesystem::path& log,
                 const std::vector<std::string>& environment) {
  std::vector<std::string> words = {TACTILE_CLI_PATH};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<std::string> entries = environment;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string name = std::string(*entry).substr(0, std::string(*entry).find('='));
    const bool replaced = std::any_of(entries.begin(), entries.end(), [&](const std::string& e) {
      return e.compare(0, name.size() + 1, name + "=") == 0;
    });
    if (!replaced) entries.emplace_back(*entry);
  }
  std::vector<char*> envp;
  for (auto& entry : entries) envp.push_back(entry.data());
  envp.push_back(nullptr);
  const int e = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (e != 0) throw std::runtime_error("cannot start " + words[0]);
}

Started::~Started() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
}

void Started::signal(int sig) const {
  ::kill(pid_, sig);
}

bool Started::wait_until_watching(int sig, double limit_s) const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  const std::filesystem::path proc = "/proc/" + std::to_string(pid_);
  for (;;) {
    std::error_code ec;
    for (const auto& fd : std::filesystem::directory_iterator(proc / "fd", ec)) {
      if (std::filesystem::read_symlink(fd.path(), ec).string() != "anon_inode:[signalfd]") {
        continue;
      }
      std::ifstream in(proc / "fdinfo" / fd.path().filename());
      std::string line;
      while (std::getline(in, line)) {
        if (line.rfind("sigmask:", 0) != 0) continue;
        const unsigned long long mask = std::stoull(line.substr(8), nullptr, 16);
        if ((mask >> (sig - 1)) & 1ULL) return true;
      }
    }
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

Started::Ended Started::wait(double limit_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  for (;;) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      if (WIFEXITED(status)) return {true, WEXITSTATUS(status), 0};
      return {true, -1, WTERMSIG(status)};
    }
    if (std::chrono::steady_clock::now() >= until) return {};
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace tactile::test
