#pragma once
// The project's one way of writing a file that may already exist: into PATH.partial, then a
// rename over PATH, so that a failed or interrupted write never destroys what was there.

#include <filesystem>
#include <functional>
#include <string>

namespace tactile {

// Calls write(partial) to fill the temporary file, then renames it over `path`. If `write`
// throws, the temporary file is removed and the exception passes on; `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& partial)>& write);

// `text` written atomically. Throws std::runtime_error "cannot write <path>".
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace tactile
