#pragma once
// The project's one way of writing a file. The bytes go into a temporary file with a random name
// in the destination's folder, created exclusively (never through a symbolic link, never one
// left by an earlier run), flushed to the disk and renamed over the destination. So a failed,
// interrupted or concurrent write never destroys what was there, never writes through a link
// planted at a predictable name, and never leaves a half-written destination. The temporary
// file is removed on every failure path, and on SIGINT and SIGTERM (see
// remove_temporary_files). Every error names the destination and the operating system's reason.

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

namespace tactile {

// One file being written. Nothing is visible at `path` until commit(); destroying an
// uncommitted AtomicFile removes its temporary file. Throws std::runtime_error
// "cannot write PATH: REASON" on any failure (REASON is the operating system's, e.g. "No space
// left on device").
class AtomicFile {
 public:
  // Creates the temporary file. Fails if the folder is missing or not writable, or if `path`
  // is a folder or anything else that is not a regular file (a device, a pipe).
  explicit AtomicFile(std::filesystem::path path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view bytes);
  // Flushes the file to the disk and renames it over `path` (replacing a symbolic link there,
  // not its target). Fails if `path` is a folder.
  void commit();

  const std::filesystem::path& path() const { return path_; }
  // The temporary file's path, for tests.
  const std::filesystem::path& temporary_path() const { return temp_; }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const;
  void discard() noexcept;

  std::filesystem::path path_, temp_;
  int fd_ = -1;
  int slot_ = -1;  // in the registry of temporary files removed on a signal; -1: none
};

// 0 if an AtomicFile for `path` could create its temporary file, else the operating system's
// error (EACCES, EROFS; ENOENT in /proc). Tries it: the file is created and removed at once, with
// SIGINT and SIGTERM held meanwhile so that a signal cannot leave it behind.
int can_create_beside(const std::filesystem::path& path) noexcept;

// `bytes` written to `path` through an AtomicFile.
void write_atomically(const std::filesystem::path& path, std::string_view bytes);

// The same for text (kept for its name at the call sites of JSON and other text files).
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// An output stream into an AtomicFile, for writers that compose text with `<<` (CSV files,
// reports). Bytes reach the temporary file as the buffer fills; commit() makes them the
// destination. The first write error is kept and thrown by commit() with the OS's reason.
class AtomicOstream : public std::ostream {
 public:
  explicit AtomicOstream(std::filesystem::path path);
  AtomicOstream(AtomicOstream&& other) noexcept;
  ~AtomicOstream() override;

  void commit();
  const std::filesystem::path& path() const;

 private:
  class Buffer;
  std::unique_ptr<Buffer> buffer_;
};

// A command's outputs made visible together at its end, or not at all. While a CommitTogether
// lives, AtomicFile::commit (in any thread) flushes and closes its temporary file but leaves it
// under its temporary name; commit() then renames them all, in the order they were committed,
// with SIGINT and SIGTERM held in the calling thread. Until then they are temporary files like
// any other: a signal removes them, and so does destroying the CommitTogether uncommitted (the
// command failed), so that a failed or stopped run replaces none of its outputs, not the first
// few. One at a time in a process. For commands of a few outputs: a signal finds only as many
// temporary files as the registry has room for (64), whether committed or being written.
class CommitTogether {
 public:
  CommitTogether();
  CommitTogether(const CommitTogether&) = delete;
  CommitTogether& operator=(const CommitTogether&) = delete;
  ~CommitTogether();

  // Renames every output written since construction over its destination; later writes are
  // committed one by one again. Throws "cannot write PATH: REASON" if a rename fails; the
  // outputs not yet renamed are then removed.
  void commit();

  struct Pending;

 private:
  std::unique_ptr<Pending> pending_;
};

// Removes every temporary file being written. Async-signal-safe: a command that installs its
// own SIGINT/SIGTERM handler calls it from there. Until then, AtomicFile installs a handler that
// calls it and then passes the signal on to the handler found before (or the default action,
// which ends the process with status 130 for SIGINT, 143 for SIGTERM).
void remove_temporary_files() noexcept;

}  // namespace tactile
