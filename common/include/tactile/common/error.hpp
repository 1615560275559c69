#pragma once
#include <stdexcept>
#include <string>

namespace tactile {

// A file or frame that does not follow its documented format. The message names the file
// (or source), the element and what is wrong.
class FormatError : public std::runtime_error {
 public:
  explicit FormatError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace tactile
