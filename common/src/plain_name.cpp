#include "tactile/common/plain_name.hpp"

#include <fmt/format.h>

namespace tactile {
namespace {

bool control(unsigned char c) {
  return c < 0x20 || c == 0x7f;
}

bool allowed(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '_' || c == '.';
}

// A hostile name may be megabytes long: the message shows its start.
constexpr std::size_t kShownBytes = 256;

std::string shown(std::string_view name) {
  std::string s;
  for (const char ch : name.substr(0, kShownBytes)) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n')
      s += "\\n";
    else if (c == '\t')
      s += "\\t";
    else if (c == '\r')
      s += "\\r";
    else if (control(c) || c >= 0x80)
      s += fmt::format("\\x{:02x}", c);
    else
      s += ch;
  }
  if (name.size() > kShownBytes) s += "...";
  return s;
}

std::optional<std::string> why_not(std::string_view name) {
  if (name.empty()) return "it is empty";
  for (const char c : name)
    if (control(static_cast<unsigned char>(c))) return "it holds a control character";
  for (const char c : name)
    if (c == '/' || c == '\\')
      return fmt::format("it holds '{}', a path separator (it must name one file)", c);
  if (name == "." || name == "..")
    return fmt::format("'{}' is a folder of every folder, not a name of its own", name);
  if (name.size() > kMaxPlainNameBytes)
    return fmt::format("it is {} bytes long, more than the {} allowed", name.size(),
                       kMaxPlainNameBytes);
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (!allowed(u))
      return fmt::format("it holds {} (only ASCII letters, digits, '-', '_' and '.' are allowed)",
                         u >= 0x80 ? fmt::format("byte 0x{:02x}", u) : fmt::format("'{}'", c));
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> plain_name_error(std::string_view field, std::string_view name) {
  const auto why = why_not(name);
  if (!why) return std::nullopt;
  return fmt::format("{} \"{}\" is not a plain name: {}", field, shown(name), *why);
}

}  // namespace tactile
