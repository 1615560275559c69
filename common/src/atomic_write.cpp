#include "tactile/common/atomic_write.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <random>
#include <stdexcept>
#include <streambuf>
#include <utility>
#include <vector>

namespace tactile {

namespace fs = std::filesystem;

namespace {

// The registry of temporary files being written, read by the SIGINT/SIGTERM handler. This is the
// project's one piece of process-wide state: a signal handler receives nothing but the signal
// number, so what it must clean up can only be found in static storage. Fixed slots of plain
// characters and lock-free atomics are what a handler may touch (no allocation, no locks). A
// write that finds every slot taken still happens; only its cleanup on a signal is lost.
constexpr int kSlots = 64;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX] = {};
};
Slot g_slots[kSlots];
struct sigaction g_previous_int {};
struct sigaction g_previous_term {};
std::once_flag g_handler_installed;

void pass_on(int sig, const struct sigaction& before, siginfo_t* info, void* context) {
  if ((before.sa_flags & SA_SIGINFO) != 0) {
    if (before.sa_sigaction != nullptr) before.sa_sigaction(sig, info, context);
    return;
  }
  if (before.sa_handler == SIG_IGN) return;
  if (before.sa_handler != SIG_DFL) {
    before.sa_handler(sig);
    return;
  }
  // The default action: end the process by this signal once the handler returns (the signal is
  // blocked until then), so the parent sees it as such (a shell reports 130 or 143).
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);
}

void on_signal(int sig, siginfo_t* info, void* context) {
  const int saved_errno = errno;
  remove_temporary_files();
  pass_on(sig, sig == SIGINT ? g_previous_int : g_previous_term, info, context);
  errno = saved_errno;
}

void install_handler() {
  struct sigaction mine {};
  mine.sa_sigaction = &on_signal;
  mine.sa_flags = SA_SIGINFO | SA_RESTART;
  sigemptyset(&mine.sa_mask);
  for (auto [sig, previous] : {std::pair{SIGINT, &g_previous_int}, {SIGTERM, &g_previous_term}}) {
    if (sigaction(sig, nullptr, previous) != 0) continue;
    // An ignored signal (a background job's SIGINT) stays ignored.
    if ((previous->sa_flags & SA_SIGINFO) == 0 && previous->sa_handler == SIG_IGN) continue;
    sigaction(sig, &mine, nullptr);
  }
}

// Blocks SIGINT and SIGTERM in this thread while a temporary file is created and registered, so
// that no signal can fall between the two.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_{};
};

int claim_slot(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kClaimed)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      return i;
    }
  }
  return -1;
}

void release_slot(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree);
}

// ".NAME.<16 hex digits>.tmp": hidden, recognisable, and unpredictable so that nothing can be
// planted at it in advance. The name part is cut so that the whole stays within NAME_MAX.
fs::path temporary_name(const fs::path& path) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  std::string name = path.filename().string().substr(0, 200);
  return path.parent_path() / fmt::format(".{}.{:016x}.tmp", name, random());
}

std::string reason(int error) {
  return std::strerror(error);
}

// The CommitTogether alive, if any: AtomicFile::commit must find it without every writer of the
// project passing it along (it is the same process-wide registry as the slots').
std::atomic<CommitTogether::Pending*> g_together{nullptr};

void fsync_folder(const fs::path& path) {
  // The rename is done; syncing the folder only makes it survive a power cut, so a failure here
  // is not reported (some file systems refuse fsync on a folder).
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace

struct CommitTogether::Pending {
  struct File {
    fs::path temp, path;
    int slot = -1;
  };
  std::mutex mutex;
  std::vector<File> files;

  void remove_from(std::size_t first) noexcept {
    for (std::size_t i = first; i < files.size(); ++i) {
      ::unlink(files[i].temp.c_str());
      release_slot(files[i].slot);
    }
    files.clear();
  }
};

CommitTogether::CommitTogether() : pending_(std::make_unique<Pending>()) {
  Pending* none = nullptr;
  if (!g_together.compare_exchange_strong(none, pending_.get())) {
    throw std::logic_error("CommitTogether: one is alive already");
  }
}

CommitTogether::~CommitTogether() {
  Pending* mine = pending_.get();
  g_together.compare_exchange_strong(mine, nullptr);
  const std::lock_guard lock(pending_->mutex);
  pending_->remove_from(0);
}

void CommitTogether::commit() {
  Pending* mine = pending_.get();
  g_together.compare_exchange_strong(mine, nullptr);
  const std::lock_guard lock(pending_->mutex);
  const SignalsBlocked blocked;
  auto& files = pending_->files;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (::rename(files[i].temp.c_str(), files[i].path.c_str()) != 0) {
      const int error = errno;
      const fs::path path = files[i].path;
      pending_->remove_from(i);
      throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), reason(error)));
    }
    release_slot(files[i].slot);
  }
  for (const auto& f : files) fsync_folder(f.path);
  files.clear();
}

void remove_temporary_files() noexcept {
  for (auto& slot : g_slots) {
    // A slot claimed but not yet live is another thread between naming its temporary file and
    // creating it, with these signals blocked there but not here: wait (briefly, nanosleep is
    // safe in a handler) for it to finish, or the file it creates would outlive the process.
    for (int waited_ms = 0; slot.state.load() == kClaimed && waited_ms < 200; ++waited_ms) {
      const timespec one_ms{0, 1'000'000};
      ::nanosleep(&one_ms, nullptr);
    }
    if (slot.state.load() == kLive) ::unlink(slot.path);
  }
}

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
  if (path_.filename().empty()) fail("no file name", EISDIR);
  // A device or a pipe at the destination (/dev/null, /dev/stdout) would be replaced by a
  // regular file, not written to.
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) fail("", EISDIR);
    throw std::runtime_error(fmt::format(
        "cannot write {}: not a regular file (a device, pipe or socket)", path_.string()));
  }
  std::call_once(g_handler_installed, install_handler);
  const SignalsBlocked blocked;
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_ = temporary_name(path_);
    slot_ = claim_slot(temp_.string());
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ >= 0) {
      if (slot_ >= 0) g_slots[slot_].state.store(kLive);
      return;
    }
    const int error = errno;
    release_slot(slot_);
    slot_ = -1;
    if (error != EEXIST) {
      temp_.clear();
      fail("cannot create a file in its folder", error);
    }
  }
  temp_.clear();
  fail("cannot create a temporary file in its folder", EEXIST);
}

AtomicFile::~AtomicFile() {
  discard();
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temp_.empty()) ::unlink(temp_.c_str());
  temp_.clear();
  release_slot(slot_);
  slot_ = -1;
}

void AtomicFile::fail(const std::string& what, int error) const {
  throw std::runtime_error(fmt::format("cannot write {}: {}{}", path_.string(),
                                       what.empty() ? "" : what + ": ", reason(error)));
}

void AtomicFile::write(std::string_view bytes) {
  if (fd_ < 0) throw std::logic_error("AtomicFile::write after commit or failure");
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      discard();
      fail("", error);
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void AtomicFile::commit() {
  if (fd_ < 0) throw std::logic_error("AtomicFile::commit after commit or failure");
  // A full disk or a failing device can show only at fsync or close (delayed allocation, NFS).
  if (::fsync(fd_) != 0) {
    const int error = errno;
    discard();
    fail("", error);
  }
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {
    const int error = errno;
    discard();
    fail("", error);
  }
  if (CommitTogether::Pending* together = g_together.load()) {
    // Handed over, still registered for removal on a signal.
    const std::lock_guard lock(together->mutex);
    together->files.push_back({temp_, path_, slot_});
    temp_.clear();
    slot_ = -1;
    return;
  }
  if (::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    discard();
    fail("", error);
  }
  temp_.clear();
  release_slot(slot_);
  slot_ = -1;
  fsync_folder(path_);
}

int can_create_beside(const fs::path& path) noexcept {
  try {
    const SignalsBlocked blocked;
    for (int attempt = 0; attempt < 100; ++attempt) {
      const fs::path temp = temporary_name(path);
      const int fd =
          ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
      if (fd >= 0) {
        ::close(fd);
        ::unlink(temp.c_str());
        return 0;
      }
      if (errno != EEXIST) return errno;
    }
    return EEXIST;
  } catch (...) {
    return ENOMEM;  // the name could not be made
  }
}

void write_atomically(const fs::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  write_atomically(path, text);
}

// A stream buffer that hands full buffers to an AtomicFile. A stream buffer cannot throw
// usefully (the stream turns it into badbit), so the first error is kept for commit().
class AtomicOstream::Buffer : public std::streambuf {
 public:
  explicit Buffer(fs::path path) : file_(std::move(path)), bytes_(1 << 16) {
    setp(bytes_.data(), bytes_.data() + bytes_.size());
  }

  void commit() {
    drain();
    if (!error_.empty()) throw std::runtime_error(error_);
    file_.commit();
  }
  const fs::path& path() const { return file_.path(); }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const std::string_view pending(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(bytes_.data(), bytes_.data() + bytes_.size());
    if (!error_.empty()) return false;
    try {
      file_.write(pending);
      return true;
    } catch (const std::exception& e) {
      error_ = e.what();
      return false;
    }
  }

  AtomicFile file_;
  std::vector<char> bytes_;
  std::string error_;
};

AtomicOstream::AtomicOstream(fs::path path)
    : std::ostream(nullptr), buffer_(std::make_unique<Buffer>(std::move(path))) {
  rdbuf(buffer_.get());
}

AtomicOstream::AtomicOstream(AtomicOstream&& other) noexcept
    : std::ostream(std::move(other)), buffer_(std::move(other.buffer_)) {
  set_rdbuf(buffer_.get());
}

AtomicOstream::~AtomicOstream() = default;

void AtomicOstream::commit() {
  buffer_->commit();
}

const fs::path& AtomicOstream::path() const {
  return buffer_->path();
}

}  // namespace tactile
