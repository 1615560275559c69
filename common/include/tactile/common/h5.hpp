#pragma once
// Thin helpers over the HDF5 C++ API shared by the capture and display file formats.
// Every failure becomes tactile::FormatError with a message naming the file, the object and
// what is wrong, because H5::Exception is not a std::exception and its messages are cryptic.

#include <H5Cpp.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include <vector>
#include "tactile/common/provenance.hpp"

#include "tactile/common/error.hpp"

namespace tactile::h5 {

// Writes a file atomically: `fill` builds the file in memory, whose bytes then replace `path`
// through write_atomically (atomic_write.hpp) only when `fill` returns normally. A failed write
// leaves an existing file untouched; errors name `path` and the OS's or HDF5's reason.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(H5::H5File&)>& fill);

// HDF5 1.10 itself crashes or hangs on some damaged files (inside its object-header and
// global-heap code, before any check of ours can run), so readers first run `read` on `path` in
// a forked child process: a child that dies, or that has not finished within a bound that grows
// with the file's size, makes this throw FormatError naming `path` and `what` ("a tactile
// movie") as a damaged file. A child that returned or threw is forgotten, and the caller then
// reads in-process, reaching the same result on the same bytes. Costs one extra read.
void read_in_child_first(const std::filesystem::path& path, const std::string& what,
                         const std::function<void()>& read);

// A reader that runs in a child process: a plain function, so that a child forked once can
// call it for any file (the same program, the same address).
using ChildRead = void (*)(const std::filesystem::path& path);

// The child of read_in_child_first kept for many files: forked at the first read, it reads
// every file sent to it over a pipe and answers, so that a program reading thousands of files
// (a fuzzer) pays for a fork only after a file that crashed or hung the child, and every
// kReadsPerChild files (HDF5 keeps a little memory per damaged file); requests and answers go
// over a socket pair. The verdicts and their
// words are read_in_child_first's, with one difference: the child carries HDF5's library state
// from file to file, so a file read after a damaged one may crash it where a fresh child would
// not, and is then called damaged too (never the reverse: what the child accepts, the caller
// reads in-process as before). For a fuzzer that is a skipped input; a program that reads a few
// files keeps a child per file. Not shared between threads.
class ReadingProcess {
 public:
  static constexpr int kReadsPerChild = 2000;
  ReadingProcess() = default;
  ~ReadingProcess();
  ReadingProcess(const ReadingProcess&) = delete;
  ReadingProcess& operator=(const ReadingProcess&) = delete;

  // Runs `read` on `path` in the child; throws FormatError naming `path` and `what` when the
  // child dies or does not answer within read_in_child_first's bound. A read that returned or
  // threw is forgotten.
  void read(const std::filesystem::path& path, const std::string& what, ChildRead read);

  // Children forked so far (for tests and for a fuzzer's statistics).
  int forks() const { return forks_; }

 private:
  void start();
  void stop();
  int child_ = -1;
  int socket_ = -1;  // requests to the child, its answers back
  int reads_ = 0;
  int forks_ = 0;
};

// read_in_child_first through `process` when given (one child for many files), else in a child
// of its own.
void read_in_child_first(const std::filesystem::path& path, const std::string& what, ChildRead read,
                         ReadingProcess* process);

// Throws FormatError saying that `path` cannot be read as `what` ("a tactile movie"): a reader
// lets no H5::Exception out raw, since it is not a std::exception.
[[noreturn]] void throw_unreadable(const std::filesystem::path& path, const std::string& what,
                                   const H5::Exception& e);

// The child's side of read_guarded: what the read returns or throws is forgotten there.
template <auto ReadChecked>
void read_and_forget(const std::filesystem::path& path) {
  static_cast<void>(ReadChecked(path));
}

// A whole reader of one format: `ReadChecked` (a plain function that reads and checks the file)
// runs first in a child (read_in_child_first, through `process` when given), then in-process,
// where HDF5's exceptions become FormatError (throw_unreadable).
template <auto ReadChecked>
auto read_guarded(const std::filesystem::path& path, const std::string& what,
                  ReadingProcess* process) {
  read_in_child_first(path, what, &read_and_forget<ReadChecked>, process);
  try {
    return ReadChecked(path);
  } catch (const H5::Exception& e) {
    throw_unreadable(path, what, e);
  }
}

// The HDF5 type of the numbers the files hold (double, float, std::int32_t).
template <typename T>
const H5::PredType& native_type();
template <>
const H5::PredType& native_type<double>();
template <>
const H5::PredType& native_type<float>();
template <>
const H5::PredType& native_type<std::int32_t>();

// Opens an existing file for reading; throws FormatError if missing or not HDF5. A file whose
// writer was killed while it grew (GrowingFile, h5_growing.hpp) opens too, and sets
// `*unfinished`: its datasets may then hold rows beyond what its counts say.
H5::H5File open_for_reading(const std::filesystem::path& path, bool* unfinished = nullptr);

void write_attr(H5::H5Object& obj, const std::string& name, double value);
void write_attr(H5::H5Object& obj, const std::string& name, std::int64_t value);
void write_attr(H5::H5Object& obj, const std::string& name, const std::string& value);
// Needed so that string literals do not convert to the numeric overloads.
inline void write_attr(H5::H5Object& obj, const std::string& name, const char* value) {
  write_attr(obj, name, std::string(value));
}

// `where` is a human-readable location for messages, e.g. "movie.h5:/deflection_um".
double read_attr_double(const H5::H5Object& obj, const std::string& name, const std::string& where);
std::int64_t read_attr_int(const H5::H5Object& obj, const std::string& name,
                           const std::string& where);
std::string read_attr_string(const H5::H5Object& obj, const std::string& name,
                             const std::string& where);
bool has_attr(const H5::H5Object& obj, const std::string& name);

// Datasets of native numbers with any shape (dims multiply to data.size()).
void write_dataset(H5::Group& group, const std::string& name, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims);
void write_dataset(H5::Group& group, const std::string& name, const std::vector<float>& data,
                   const std::vector<hsize_t>& dims);
void write_dataset(H5::Group& group, const std::string& name, const std::vector<std::int32_t>& data,
                   const std::vector<hsize_t>& dims);

// Reads a dataset, checking that it exists, is of the expected number class (float or integer)
// and rank; returns its dims in `dims`. Throws FormatError naming the problem.
std::vector<double> read_doubles(const H5::Group& group, const std::string& name, std::size_t rank,
                                 std::vector<hsize_t>& dims, const std::string& where);
std::vector<float> read_floats(const H5::Group& group, const std::string& name, std::size_t rank,
                               std::vector<hsize_t>& dims, const std::string& where);
std::vector<std::int32_t> read_ints(const H5::Group& group, const std::string& name,
                                    std::size_t rank, std::vector<hsize_t>& dims,
                                    const std::string& where);

bool has_child(const H5::Group& group, const std::string& name);
H5::Group open_group(const H5::Group& parent, const std::string& name, const std::string& where);

// Current UTC time as ISO 8601, for provenance attributes.
std::string utc_now_iso8601();

// A provenance as the attributes provenance_input, provenance_program_version,
// provenance_command_line, provenance_method, provenance_parameters_json and
// provenance_created_utc (the time of writing when created_utc is empty).
void write_provenance(H5::H5Object& obj, const Provenance& provenance);
// Reads them back. An attribute that is absent reads as empty (a file from another tool may have
// none); files written before these names held provenance_source, provenance_mapping_method and
// provenance_mapping_parameters_json, read as input, method and parameters_json.
Provenance read_provenance(const H5::H5Object& obj, const std::string& where);

}  // namespace tactile::h5
