#include "tactile/common/stop_signals.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace tactile {

namespace {

// SIGINT and SIGTERM, less one the process ignores: the kernel discards an ignored signal only
// while it is not blocked, so blocking it would turn it into a stop request.
sigset_t stop_set() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : {SIGINT, SIGTERM}) {
    struct sigaction now {};
    if (sigaction(sig, nullptr, &now) == 0 && (now.sa_flags & SA_SIGINFO) == 0 &&
        now.sa_handler == SIG_IGN) {
      continue;
    }
    sigaddset(&set, sig);
  }
  return set;
}

}  // namespace

StopSignals::StopSignals() {
  const sigset_t set = stop_set();
  if (const int e = pthread_sigmask(SIG_BLOCK, &set, &old_mask_); e != 0) {
    throw std::runtime_error(std::string("cannot block SIGINT and SIGTERM: ") + std::strerror(e));
  }
  fd_ = signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
  if (fd_ < 0) {
    const int e = errno;
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    throw std::runtime_error(std::string("cannot watch SIGINT and SIGTERM: ") + std::strerror(e));
  }
}

StopSignals::~StopSignals() {
  ::close(fd_);
  pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
}

int StopSignals::received() {
  if (received_ != 0) return received_;
  signalfd_siginfo info{};
  if (::read(fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    received_ = static_cast<int>(info.ssi_signo);
  }
  return received_;
}

bool stop_requested(int stop_fd) {
  if (stop_fd < 0) return false;
  pollfd p{stop_fd, POLLIN, 0};
  return ::poll(&p, 1, 0) > 0 && (p.revents & POLLIN) != 0;
}

}  // namespace tactile
