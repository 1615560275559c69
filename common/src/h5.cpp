#include "tactile/common/h5.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <initializer_list>
#include <system_error>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <string>

#include "provenance_fields.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/value_checks.hpp"
#include "utc_now.hpp"

// Set by a sanitizer runtime when one is linked in (weak: absent otherwise). Its death callback
// is how a fuzzer records a crash; in the reading child a crash is a finding about the file.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace tactile::h5 {

template <>
const H5::PredType& native_type<double>() {
  return H5::PredType::NATIVE_DOUBLE;
}
template <>
const H5::PredType& native_type<float>() {
  return H5::PredType::NATIVE_FLOAT;
}
template <>
const H5::PredType& native_type<std::int32_t>() {
  return H5::PredType::NATIVE_INT32;
}

namespace {

// HDF5 prints its own error stack to stderr on every failure; our FormatError says it better.
void silence_hdf5() {
  H5::Exception::dontPrint();
}

std::string describe(const H5::Exception& e) {
  return e.getDetailMsg().empty() ? std::string("HDF5 error") : e.getDetailMsg();
}

template <typename T>
void write_any(H5::Group& group, const std::string& name, const std::vector<T>& data,
               const std::vector<hsize_t>& dims) {
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count != data.size()) {
    throw std::logic_error(
        fmt::format("dataset {}: {} values do not fill the shape", name, data.size()));
  }
  H5::DataSpace space(static_cast<int>(dims.size()), dims.data());
  H5::DSetCreatPropList props;
  // No modification time in the object's header: the same data written twice gives the same
  // bytes (the file's one time is its provenance's, which SOURCE_DATE_EPOCH can fix).
  H5Pset_obj_track_times(props.getId(), false);
  // Compress large datasets: movies are mostly smooth and compress several-fold.
  if (count >= 4096 && !dims.empty()) {
    std::vector<hsize_t> chunk(dims);
    chunk[0] = std::min<hsize_t>(
        dims[0], std::max<hsize_t>(1, 65536 / std::max<hsize_t>(1, count / dims[0])));
    for (auto& c : chunk) c = std::max<hsize_t>(c, 1);
    props.setChunk(static_cast<int>(chunk.size()), chunk.data());
    props.setDeflate(4);
  }
  H5::DataSet ds = group.createDataSet(name, native_type<T>(), space, props);
  if (count > 0) ds.write(data.data(), native_type<T>());
}

// Deflate, the one filter our files use, shrinks data at most 1032:1.
constexpr double kMaxDeflateRatio = 1032;

// A damaged header can declare far more values than the file holds: allocating them before
// HDF5's read fails took gigabytes and seconds. What the file stores (no more than the file
// itself), expanded by deflate's largest ratio, bounds what a dataset can hold.
void check_stored(const H5::DataSet& ds, std::uint64_t count, const std::string& loc) {
  if (count == 0) return;
  const hsize_t stored = ds.getStorageSize();
  hsize_t file_bytes = 0;
  const hid_t file = H5Iget_file_id(ds.getId());
  if (file >= 0) {
    if (H5Fget_filesize(file, &file_bytes) < 0) file_bytes = 0;
    H5Fclose(file);
  }
  if (file_bytes > 0 && stored > file_bytes) {
    throw FormatError(fmt::format("{}: declares {} bytes of stored data in a file of {} bytes", loc,
                                  stored, file_bytes));
  }
  // The size of a value as stored: a damaged type can declare gigabytes for each.
  const std::size_t value_bytes = ds.getDataType().getSize();
  const double bytes = static_cast<double>(count) * static_cast<double>(value_bytes);
  if (bytes > static_cast<double>(stored) * kMaxDeflateRatio) {
    throw FormatError(
        fmt::format("{}: declares {} values of {} bytes each ({} bytes) but the file "
                    "stores {} bytes of them (at most 1:{} compressed)",
                    loc, count, value_bytes, bytes, stored, kMaxDeflateRatio));
  }
}

template <typename T>
std::vector<T> read_any(const H5::Group& group, const std::string& name, std::size_t rank,
                        std::vector<hsize_t>& dims, const std::string& where, H5T_class_t want) {
  const std::string loc = fmt::format("{}/{}", where, name);
  if (!has_child(group, name)) throw FormatError(fmt::format("{}: dataset is missing", loc));
  try {
    H5::DataSet ds = group.openDataSet(name);
    if (ds.getTypeClass() != want) {
      throw FormatError(fmt::format("{}: expected {} values, found another type", loc,
                                    want == H5T_FLOAT ? "floating-point" : "integer"));
    }
    H5::DataSpace space = ds.getSpace();
    const int file_rank = space.getSimpleExtentNdims();
    if (file_rank < 0 || static_cast<std::size_t>(file_rank) != rank) {
      throw FormatError(
          fmt::format("{}: expected {} dimension(s), found {}", loc, rank, file_rank));
    }
    dims.assign(rank, 0);
    if (rank > 0) space.getSimpleExtentDims(dims.data());
    // Before allocating: a damaged or hostile shape must fail here, not in the allocator.
    const auto count = checks::value_count(std::vector<std::uint64_t>(dims.begin(), dims.end()),
                                           sizeof(T), where, name);
    check_stored(ds, count, loc);
    std::vector<T> out(count);
    if (count > 0) ds.read(out.data(), native_type<T>());
    return out;
  } catch (const H5::Exception& e) {
    throw FormatError(fmt::format("{}: cannot read ({})", loc, describe(e)));
  }
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(H5::H5File&)>& fill) {
  silence_hdf5();
  // The file is built in memory (the core driver without a backing store) and its bytes are
  // written by write_atomically. HDF5 then never touches the disk: a full disk is our write()'s
  // error with the OS's reason, not a failure deep inside HDF5's close, and the temporary file
  // is created exclusively like every other output's. The cost is the file's (compressed) size
  // in memory, twice for a moment while the image is copied out.
  std::vector<char> image;
  try {
    H5::FileAccPropList access;
    access.setCore(std::size_t{4} << 20, false);
    H5::H5File file(path.string(), H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, access);
    fill(file);
    file.flush(H5F_SCOPE_GLOBAL);
    const ssize_t size = H5Fget_file_image(file.getId(), nullptr, 0);
    if (size < 0) throw H5::FileIException("H5Fget_file_image", "cannot get the file image");
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file.getId(), image.data(), image.size()) != size) {
      throw H5::FileIException("H5Fget_file_image", "cannot get the file image");
    }
    file.close();
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), describe(e)));
  }
  write_atomically(path, std::string_view(image.data(), image.size()));
}

namespace {

// Generous for any disk: a child still reading after this is stuck in a damaged structure.
int read_limit_s(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  return 10 + static_cast<int>((ec ? 0 : size) / (4 << 20));
}

// In a reading child just forked: it dies with its parent, a crash ends it by its signal, and
// Ctrl-C is the parent's. Returns false when the parent ended before PDEATHSIG was set.
bool become_reading_child(pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) return false;
  // A crash is the child's verdict on the file: it ends the child by its signal, reported by
  // the parent, not by whatever handler the process installed.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
  // Ctrl-C is the parent's to handle (its handler removes the parent's temporary files); the
  // child ends with the parent through PDEATHSIG.
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  if (&__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
  return true;
}

// Waits until `fd` is readable or closed, or `limit_s` has passed (false).
bool wait_readable(int fd, int limit_s) {
  pollfd pfd{fd, POLLIN, 0};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limit_s);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    const int n = ::poll(&pfd, 1, static_cast<int>(left.count()));
    if (n > 0 || (n < 0 && errno != EINTR)) return true;
  }
}

int reap(pid_t child) {
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// The damaged-file error for a child that did not finish (timed out) or ended by `status`.
FormatError damaged(const std::filesystem::path& path, const std::string& what, int limit_s,
                    bool timed_out, int status) {
  if (timed_out) {
    return FormatError(fmt::format("{}: damaged file: reading it as {} did not finish within {} s",
                                   path.string(), what, limit_s));
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return FormatError(
        fmt::format("{}: damaged file: reading it as {} crashed the HDF5 library "
                    "(signal {}, {})",
                    path.string(), what, sig, ::strsignal(sig)));
  }
  return FormatError(
      fmt::format("{}: damaged file: reading it as {} crashed the HDF5 library "
                  "(exit status {})",
                  path.string(), what, WIFEXITED(status) ? WEXITSTATUS(status) : -1));
}

// Over the reading child's socket: a child that has died is EPIPE here, not a SIGPIPE that
// would end the caller.
bool send_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// A request to the reading child: the reader's address, the path's length, the path.
struct ReadRequest {
  ChildRead read;
  std::uint32_t path_bytes;
};

[[noreturn]] void serve_reads(int socket) {
  for (;;) {
    ReadRequest request{};
    if (!read_all(socket, &request, sizeof request) || request.path_bytes > (1u << 20)) {
      ::_exit(0);
    }
    std::string path(request.path_bytes, '\0');
    if (!read_all(socket, path.data(), path.size())) ::_exit(0);
    try {
      request.read(path);
    } catch (...) {
    }
    const char done = 'k';
    if (!send_all(socket, &done, 1)) ::_exit(0);
  }
}

// Forks a reading child joined to this process by `ends` (a pipe or a socket pair): the child
// keeps ends[1], runs `work` on it and exits without atexit handlers or flushing the parent's
// buffers; this process keeps ends[0]. Returns the child, or -1 with both ends closed when
// fork fails.
template <typename Work>
pid_t fork_reading_child(const int (&ends)[2], Work work) {
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(ends[0]);
    ::close(ends[1]);
    return -1;
  }
  if (child == 0) {
    ::close(ends[0]);
    if (become_reading_child(parent)) work(ends[1]);
    ::_exit(0);
  }
  ::close(ends[1]);
  return child;
}

}  // namespace

void read_in_child_first(const std::filesystem::path& path, const std::string& what,
                         const std::function<void()>& read) {
  const int limit_s = read_limit_s(path);
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return;  // no protection, but still a reader
  const pid_t child = fork_reading_child(pipe_fds, [&](int) {
    try {
      read();
    } catch (...) {
    }
  });
  if (child < 0) return;
  // The pipe's write end closes when the child ends, however it ends.
  const bool timed_out = !wait_readable(pipe_fds[0], limit_s);
  ::close(pipe_fds[0]);
  if (timed_out) ::kill(child, SIGKILL);
  const int status = reap(child);
  if (timed_out || WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0)) {
    throw damaged(path, what, limit_s, timed_out, status);
  }
}

void read_in_child_first(const std::filesystem::path& path, const std::string& what, ChildRead read,
                         ReadingProcess* process) {
  if (process != nullptr) {
    process->read(path, what, read);
  } else {
    read_in_child_first(path, what, [&] { read(path); });
  }
}

void throw_unreadable(const std::filesystem::path& path, const std::string& what,
                      const H5::Exception& e) {
  throw FormatError(fmt::format("{}: cannot read as {} (damaged file?): {}", path.string(), what,
                                e.getDetailMsg()));
}

ReadingProcess::~ReadingProcess() {
  stop();
}

void ReadingProcess::start() {
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) return;
  const pid_t child = fork_reading_child(ends, serve_reads);
  if (child < 0) return;
  child_ = child;
  socket_ = ends[0];
  reads_ = 0;
  ++forks_;
}

void ReadingProcess::stop() {
  if (child_ < 0) return;
  ::close(socket_);  // the child ends at the end of its requests
  ::kill(child_, SIGKILL);
  reap(child_);
  child_ = socket_ = -1;
}

void ReadingProcess::read(const std::filesystem::path& path, const std::string& what,
                          ChildRead read) {
  if (child_ >= 0 && reads_ >= kReadsPerChild) stop();
  if (child_ < 0) start();
  if (child_ < 0) return;  // no protection, but still a reader
  ++reads_;
  const std::string text = path.string();
  const ReadRequest request{read, static_cast<std::uint32_t>(text.size())};
  // A child ended from outside (the OOM killer) cannot take the request: a child of its own.
  if (!send_all(socket_, &request, sizeof request) ||
      !send_all(socket_, text.data(), text.size())) {
    stop();
    read_in_child_first(path, what, read, nullptr);
    return;
  }
  const int limit_s = read_limit_s(path);
  const bool answered = wait_readable(socket_, limit_s);
  char done = 0;
  if (answered && read_all(socket_, &done, 1)) return;
  // No answer: the child died on this file, or is stuck in it.
  if (!answered) ::kill(child_, SIGKILL);
  const int status = reap(child_);
  ::close(socket_);
  child_ = socket_ = -1;
  throw damaged(path, what, limit_s, !answered, status);
}

H5::H5File open_for_reading(const std::filesystem::path& path, bool* unfinished) {
  if (unfinished != nullptr) *unfinished = false;
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw FormatError(fmt::format("{}: no such file", path.string()));
  }
  if (std::filesystem::file_size(path, ec) == 0) {
    throw FormatError(fmt::format("{}: file is empty", path.string()));
  }
  try {
    if (!H5::H5File::isHdf5(path.string())) {
      throw FormatError(fmt::format("{}: not an HDF5 file", path.string()));
    }
    try {
      return H5::H5File(path.string(), H5F_ACC_RDONLY);
    } catch (const H5::Exception&) {
      // A file whose writer was killed while it grew (GrowingFile, h5_growing.hpp) is still
      // marked as open for writing, which only a reader in SWMR mode accepts; a damaged file
      // fails this too and is reported with this open's reason.
      H5::H5File file(path.string(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ);
      if (unfinished != nullptr) *unfinished = true;
      return file;
    }
  } catch (const H5::Exception& e) {
    throw FormatError(fmt::format("{}: cannot open as HDF5 (truncated or damaged?): {}",
                                  path.string(), describe(e)));
  }
}

void write_attr(H5::H5Object& obj, const std::string& name, double value) {
  H5::Attribute a = obj.createAttribute(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace());
  a.write(H5::PredType::NATIVE_DOUBLE, &value);
}

void write_attr(H5::H5Object& obj, const std::string& name, std::int64_t value) {
  H5::Attribute a = obj.createAttribute(name, H5::PredType::NATIVE_INT64, H5::DataSpace());
  a.write(H5::PredType::NATIVE_INT64, &value);
}

void write_attr(H5::H5Object& obj, const std::string& name, const std::string& value) {
  // Fixed-length, null-padded UTF-8 (h5py reads bytes, MATLAB a char array): reading a
  // variable-length string goes through HDF5's global heap, whose code crashes or hangs on
  // damaged files. An empty string still needs one byte of storage.
  H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(value.size(), 1));
  type.setCset(H5T_CSET_UTF8);
  type.setStrpad(H5T_STR_NULLPAD);
  H5::Attribute a = obj.createAttribute(name, type, H5::DataSpace());
  std::string stored = value;
  stored.resize(type.getSize(), '\0');
  a.write(type, stored.data());
}

bool has_attr(const H5::H5Object& obj, const std::string& name) {
  try {
    return obj.attrExists(name);
  } catch (const H5::Exception&) {
    return false;
  }
}

namespace {
// Attribute strings are names, versions and provenance: a megabyte is far beyond any of them.
constexpr std::size_t kMaxAttributeStringBytes = 1 << 20;

H5::Attribute open_attr(const H5::H5Object& obj, const std::string& name,
                        const std::string& where) {
  if (!obj.attrExists(name)) {
    throw FormatError(fmt::format("{}: attribute '{}' is missing", where, name));
  }
  return obj.openAttribute(name);
}

void require_scalar(const H5::Attribute& a, const std::string& name, const std::string& where) {
  if (a.getSpace().getSimpleExtentNpoints() != 1) {
    throw FormatError(fmt::format("{}: attribute '{}' must be a single value", where, name));
  }
}

// The attribute `name` of `obj`, one value of a class in `classes` (else "must be `kind`"), as
// `read` gives it; HDF5's own errors become FormatError naming the attribute, as every other
// problem with it does.
template <typename Read>
auto read_scalar_attr(const H5::H5Object& obj, const std::string& name, const std::string& where,
                      std::initializer_list<H5T_class_t> classes, const char* kind, Read read) {
  try {
    H5::Attribute a = open_attr(obj, name, where);
    if (std::find(classes.begin(), classes.end(), a.getTypeClass()) == classes.end()) {
      throw FormatError(fmt::format("{}: attribute '{}' must be {}", where, name, kind));
    }
    require_scalar(a, name, where);
    return read(a);
  } catch (const H5::Exception& e) {
    throw FormatError(fmt::format("{}: attribute '{}': {}", where, name, describe(e)));
  }
}
}  // namespace

double read_attr_double(const H5::H5Object& obj, const std::string& name,
                        const std::string& where) {
  return read_scalar_attr(obj, name, where, {H5T_FLOAT, H5T_INTEGER}, "a number",
                          [](H5::Attribute& a) {
                            double v = 0;
                            a.read(H5::PredType::NATIVE_DOUBLE, &v);
                            return v;
                          });
}

std::int64_t read_attr_int(const H5::H5Object& obj, const std::string& name,
                           const std::string& where) {
  return read_scalar_attr(obj, name, where, {H5T_INTEGER}, "an integer", [](H5::Attribute& a) {
    std::int64_t v = 0;
    a.read(H5::PredType::NATIVE_INT64, &v);
    return v;
  });
}

std::string read_attr_string(const H5::H5Object& obj, const std::string& name,
                             const std::string& where) {
  return read_scalar_attr(obj, name, where, {H5T_STRING}, "a string", [&](H5::Attribute& a) {
    // Through the C API: the C++ wrapper calls strlen on whatever a damaged file yields,
    // including a null pointer.
    const H5::StrType type = a.getStrType();
    if (type.isVariableStr()) {
      char* text = nullptr;
      if (H5Aread(a.getId(), type.getId(), &text) < 0 || text == nullptr) {
        if (text != nullptr) H5free_memory(text);
        throw FormatError(fmt::format("{}: attribute '{}' holds no readable string", where, name));
      }
      std::string v(text);
      H5free_memory(text);
      return v;
    }
    const std::size_t size = type.getSize();
    if (size > kMaxAttributeStringBytes) {
      throw FormatError(fmt::format("{}: attribute '{}' declares a string of {} bytes (limit {})",
                                    where, name, size, kMaxAttributeStringBytes));
    }
    std::string v(size, '\0');
    if (size > 0 && H5Aread(a.getId(), type.getId(), v.data()) < 0) {
      throw FormatError(fmt::format("{}: attribute '{}' cannot be read", where, name));
    }
    v.resize(std::min(v.size(), v.find('\0')));
    return v;
  });
}

void write_dataset(H5::Group& group, const std::string& name, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims) {
  write_any(group, name, data, dims);
}
void write_dataset(H5::Group& group, const std::string& name, const std::vector<float>& data,
                   const std::vector<hsize_t>& dims) {
  write_any(group, name, data, dims);
}
void write_dataset(H5::Group& group, const std::string& name, const std::vector<std::int32_t>& data,
                   const std::vector<hsize_t>& dims) {
  write_any(group, name, data, dims);
}

std::vector<double> read_doubles(const H5::Group& group, const std::string& name, std::size_t rank,
                                 std::vector<hsize_t>& dims, const std::string& where) {
  return read_any<double>(group, name, rank, dims, where, H5T_FLOAT);
}
std::vector<float> read_floats(const H5::Group& group, const std::string& name, std::size_t rank,
                               std::vector<hsize_t>& dims, const std::string& where) {
  return read_any<float>(group, name, rank, dims, where, H5T_FLOAT);
}
std::vector<std::int32_t> read_ints(const H5::Group& group, const std::string& name,
                                    std::size_t rank, std::vector<hsize_t>& dims,
                                    const std::string& where) {
  return read_any<std::int32_t>(group, name, rank, dims, where, H5T_INTEGER);
}

bool has_child(const H5::Group& group, const std::string& name) {
  try {
    return group.nameExists(name);
  } catch (const H5::Exception&) {
    return false;
  }
}

H5::Group open_group(const H5::Group& parent, const std::string& name, const std::string& where) {
  if (!has_child(parent, name)) {
    throw FormatError(fmt::format("{}: group '{}' is missing", where, name));
  }
  try {
    return parent.openGroup(name);
  } catch (const H5::Exception& e) {
    throw FormatError(fmt::format("{}: '{}' is not a group ({})", where, name, describe(e)));
  }
}

void write_provenance(H5::H5Object& obj, const Provenance& provenance) {
  Provenance p = provenance;
  if (p.created_utc.empty()) p.created_utc = utc_now_iso8601();
  for (const auto& f : kProvenanceFields)
    write_attr(obj, std::string("provenance_") + f.name, p.*f.field);
}

Provenance read_provenance(const H5::H5Object& obj, const std::string& where) {
  Provenance p;
  for (const auto& f : kProvenanceFields) {
    // The current name, else the former one, else empty.
    for (const char* name : {f.name, f.former_name}) {
      if (name == nullptr) continue;
      const std::string attr = std::string("provenance_") + name;
      if (has_attr(obj, attr)) {
        p.*f.field = read_attr_string(obj, attr, where);
        break;
      }
    }
  }
  return p;
}

std::string utc_now_iso8601() {
  return tactile::utc_now_iso8601();
}

}  // namespace tactile::h5
