#include "tactile/common/output_paths.hpp"

#include "tactile/common/atomic_write.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include <map>
#include <system_error>
#include <utility>

namespace tactile {

namespace fs = std::filesystem;

namespace {

// The absolute path with "." and ".." resolved but links kept: two spellings of one path.
fs::path spelled(const fs::path& p) {
  std::error_code ec;
  const fs::path abs = fs::absolute(p, ec);
  return (ec ? p : abs).lexically_normal();
}

// The absolute path with symbolic links resolved as far as the path exists.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(spelled(p), ec);
  return ec ? spelled(p) : r;
}

// One key per file: device and inode when the path exists (so every link to a file has the same
// key), the resolved path when it does not. stat() rather than fs::equivalent: a command can
// write thousands of files and read thousands, and keys compare in a map, not pair by pair.
std::string identity(const fs::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0) {
    return "inode " + std::to_string(st.st_dev) + " " + std::to_string(st.st_ino);
  }
  return "path " + resolved(p).string();
}

// How `written` reaches the file `existing` names, for the message.
std::string through(const fs::path& written, const fs::path& existing) {
  if (spelled(written) == spelled(existing)) return "";
  if (resolved(written) == resolved(existing)) return " (the same file through a symbolic link)";
  return " (the same file through a hard link)";
}

// "--out S.h5" or, for a file inside a folder output, "--csv DIR (its tracks.csv)".
std::string describe(const Output& output, const fs::path& file) {
  if (!output.folder || file == output.path) {
    return fmt::format("{} {}", output.option, output.path.string());
  }
  return fmt::format("{} {} (its {})", output.option, output.path.string(),
                     file.lexically_relative(output.path).string());
}

// Whether `p`'s extension is `extension`, ignoring ASCII case (".PNG" is a PNG too).
bool ends_in(const fs::path& p, const std::string& extension) {
  const std::string e = p.extension().string();
  return e.size() == extension.size() &&
         std::equal(e.begin(), e.end(), extension.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

}  // namespace

Output output_file(std::string option, fs::path path) {
  return {std::move(option), std::move(path), false, {}, {}, {}};
}

Output output_file_ending(std::string option, fs::path path, std::string extension) {
  Output output = output_file(std::move(option), std::move(path));
  output.extension = std::move(extension);
  return output;
}

Output output_folder(std::string option, fs::path path, std::vector<fs::path> files,
                     std::vector<fs::path> subfolders) {
  return {std::move(option), std::move(path), true, std::move(files), std::move(subfolders), {}};
}

bool same_file(const fs::path& a, const fs::path& b) {
  return identity(a) == identity(b);
}

void refuse_output_over_input(const std::vector<Output>& outputs,
                              const std::vector<NamedPath>& inputs) {
  std::map<std::string, const NamedPath*> by_identity;
  for (const auto& in : inputs) by_identity.emplace(identity(in.path), &in);

  const auto refuse_if_input = [&](const Output& output, const fs::path& file) {
    const auto hit = by_identity.find(identity(file));
    if (hit == by_identity.end()) return;
    const NamedPath& in = *hit->second;
    throw OutputIsInputError(fmt::format(
        "{} would write over the input {} {}{}; choose another path for {}", describe(output, file),
        in.option, in.path.string(), through(file, in.path), output.option));
  };

  std::map<std::string, std::pair<const Output*, fs::path>> written;
  const auto refuse_if_written_twice = [&](const Output& output, const fs::path& file) {
    const auto [at, added] = written.emplace(identity(file), std::pair{&output, file});
    if (added) return;
    const auto& [first, first_file] = at->second;
    throw OutputIsInputError(fmt::format(
        "{} and {} would write the same file{}; give them "
        "different paths",
        describe(*first, first_file), describe(output, file), through(file, first_file)));
  };

  for (const auto& output : outputs) {
    if (!output.folder) {
      refuse_if_input(output, output.path);
      refuse_if_written_twice(output, output.path);
      continue;
    }
    // A folder output may be an input's folder: what matters is the files written into it.
    std::error_code ec;
    if (!fs::is_directory(output.path, ec)) refuse_if_input(output, output.path);
    for (const auto& name : output.files) {
      refuse_if_input(output, output.path / name);
      refuse_if_written_twice(output, output.path / name);
    }
    for (const auto& sub : output.subfolders) {
      const fs::path dir = output.path / sub;
      if (!fs::is_directory(dir, ec)) continue;
      const auto options = fs::directory_options::skip_permission_denied;
      for (auto it = fs::recursive_directory_iterator(dir, options, ec);
           !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (!it->is_directory(ec)) refuse_if_input(output, it->path());
      }
    }
  }
  for (const auto& output : outputs) refuse_unwritable_output(output);
}

void refuse_unwritable_output(const Output& output) {
  const auto refuse = [&](const std::string& why) {
    throw UnwritableOutputError(fmt::format("{} {}: {}", output.option, output.path.string(), why));
  };
  // An empty path reached HDF5 as "H5Fcreate failed", and `play --preview ""` wrote nothing
  // and said nothing.
  if (output.path.empty()) {
    throw UnwritableOutputError(fmt::format("{}: the path is empty; give a {} name", output.option,
                                            output.folder ? "folder" : "file"));
  }
  // A folder that will hold new files (and is searched): W_OK for the entry, X_OK to reach it.
  const auto refuse_unless_writable_folder = [&](const fs::path& folder) {
    std::error_code ec;
    if (!fs::exists(folder, ec))
      refuse(fmt::format("the folder {} does not exist", folder.string()));
    if (!fs::is_directory(folder, ec)) refuse(fmt::format("{} is not a folder", folder.string()));
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
      refuse(
          fmt::format("cannot write in the folder {}: {}", folder.string(), std::strerror(errno)));
    }
    if (const int error = can_create_beside(folder / "output"); error != 0) {
      refuse(fmt::format("cannot create a file in the folder {}: {}", folder.string(),
                         std::strerror(error)));
    }
  };
  const auto parent_of = [](const fs::path& p) {
    const fs::path parent = spelled(p).parent_path();
    return parent.empty() ? fs::path(".") : parent;
  };
  std::error_code ec;
  const auto status = fs::status(output.path, ec);
  if (!output.folder) {
    if (fs::is_directory(status)) refuse("is a folder; give a file name");
    if (!output.extension.empty() && !ends_in(output.path, output.extension)) {
      refuse(
          fmt::format("the name must end in {} (the format it is written in)", output.extension));
    }
    if (fs::exists(status) && !fs::is_regular_file(status)) {
      refuse("is not a regular file (a device, pipe or socket)");
    }
    refuse_unless_writable_folder(parent_of(output.path));
    return;
  }
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) refuse("is a file, not a folder");
    refuse_unless_writable_folder(output.path);
    for (const auto& name : output.files) {
      if (fs::is_directory(output.path / name, ec)) {
        throw UnwritableOutputError(fmt::format("{} {} (its {}): is a folder", output.option,
                                                output.path.string(), name.string()));
      }
    }
    return;
  }
  // Created with its missing parents: the nearest existing one must take a new folder.
  fs::path existing = parent_of(output.path);
  while (!fs::exists(existing, ec) && existing != existing.root_path() &&
         !existing.parent_path().empty()) {
    existing = existing.parent_path();
  }
  refuse_unless_writable_folder(existing);
}

}  // namespace tactile
