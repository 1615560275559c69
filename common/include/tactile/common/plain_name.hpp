#pragma once
// Names read from a file or a command line that the program makes part of a path or of a line
// of a script: an experiment's name (its default folder NAME-results), its sources' and
// layouts' names (movies, plots, perception tables, the manifest), Slurm partitions. Each must
// be one plain file name, so that it can neither reach outside the folder it is put in, nor
// end a line of a manifest or a script, nor make a file name the file system refuses halfway
// through the work.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace tactile {

// The longest plain name, in bytes. A run's movie is named after its source and its layout
// with about 40 bytes more (index, method, strain, extension); two names of this length keep
// that under the 255 bytes a file name may have on every common file system.
inline constexpr std::size_t kMaxPlainNameBytes = 100;

// Nothing when `name` is a plain name: 1 to kMaxPlainNameBytes bytes of ASCII letters, digits,
// '-', '_' and '.', other than "." and "..". Otherwise the message
// `<field> "<name>" is not a plain name: <why>`, with the name's control characters and other
// bytes outside printable ASCII written as escapes (\n, \x00), so the message stays one line
// and shows what the file holds.
std::optional<std::string> plain_name_error(std::string_view field, std::string_view name);

}  // namespace tactile
