#pragma once
// Refusing to write over one's own input. A command lists the paths it reads and the paths it
// will write, each named by the option or argument that gave it, and checks them before any
// work: an output that is an input (the same path, or the same file through a symbolic or hard
// link) would destroy the input, and the run that read it could not be repeated.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace tactile {

// An output path that cannot be used, found before any work. The `tactile` program treats it
// as a usage error.
class OutputPathError : public std::invalid_argument {
 public:
  explicit OutputPathError(const std::string& what) : std::invalid_argument(what) {}
};

// An output path that would write over an input (or over another output). The message names
// both options and both paths.
class OutputIsInputError : public OutputPathError {
 public:
  explicit OutputIsInputError(const std::string& what) : OutputPathError(what) {}
};

// An output that cannot be written: its folder is missing or not writable, a file output is a
// folder (or a device), a folder output is a file. The message names the option, the path and
// the reason.
class UnwritableOutputError : public OutputPathError {
 public:
  explicit UnwritableOutputError(const std::string& what) : OutputPathError(what) {}
};

// A path as the user gave it, with the option or argument it came from ("--out", "STRAIN_H5").
struct NamedPath {
  std::string option;
  std::filesystem::path path;
};

// What a command writes. A file output is one file. A folder output is the folder itself (which
// must not be an input file; it may be an input's folder), the files it writes there (`files`,
// relative to the folder) and the sub-folders whose contents it writes under names it makes
// up (`subfolders`: every existing file in them counts as overwritten).
struct Output {
  std::string option;
  std::filesystem::path path;
  bool folder = false;
  std::vector<std::filesystem::path> files;
  std::vector<std::filesystem::path> subfolders;
  // A file output whose format its name decides (an image encoder picks it by the extension;
  // other tools pick their reader by it): the extension it must have (".png"), compared
  // ignoring case; empty: any name.
  std::string extension;
};

// A file output at `path`, given by `option`.
Output output_file(std::string option, std::filesystem::path path);

// A file output whose name must end in `extension` (".png"): an encoder chooses the format by
// the name, so a name without it ("preview", "/proc/version") could not be written, and a file
// misnamed (a WAV called x.hjif) is one that no other tool would open.
Output output_file_ending(std::string option, std::filesystem::path path, std::string extension);

// A folder output at `path` into which the command writes `files` and the contents of
// `subfolders`.
Output output_folder(std::string option, std::filesystem::path path,
                     std::vector<std::filesystem::path> files,
                     std::vector<std::filesystem::path> subfolders = {});

// True if `a` and `b` name the same file or folder: the same inode when both exist (following
// symbolic links, so hard links and symbolic links count), else the same normalised absolute
// path.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws OutputIsInputError if any file an output writes is one of `inputs` (files or folders),
// if a folder output is an input that is not a folder, or if two outputs write the same file;
// then UnwritableOutputError if an output cannot be written (see refuse_unwritable_output).
// Changes nothing on disk (it reads folder listings of existing sub-folders, and tries whether
// each output's folder takes a new file, removing it at once).
void refuse_output_over_input(const std::vector<Output>& outputs,
                              const std::vector<NamedPath>& inputs);

// Throws UnwritableOutputError if `output` cannot be written: a file output that is a folder or
// not a regular file, whose name lacks its required extension, or whose folder is missing, not a
// folder or not writable; a folder output that is not a folder, or (when it does not exist yet)
// whose nearest existing parent cannot take a new folder; a file a folder output writes that is
// a folder. Whether a folder takes new files is tried (an empty file created and removed there,
// as atomic_write.hpp's can_create_beside): permissions alone do not tell, for the superuser
// passes them everywhere, and /proc or /sys refuse new files whatever they say.
void refuse_unwritable_output(const Output& output);

}  // namespace tactile
