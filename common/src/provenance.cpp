#include "tactile/common/provenance.hpp"

#include <fmt/format.h>

#include <utility>

#include "tactile/common/h5.hpp"
#include "tactile/common/version.hpp"

namespace tactile {

Provenance make_provenance(std::string input, std::string method, std::string parameters_json) {
  Provenance p;
  p.input = std::move(input);
  p.program_version = kVersion;
  p.method = std::move(method);
  p.parameters_json = std::move(parameters_json);
  p.created_utc = h5::utc_now_iso8601();
  return p;
}

std::string command_line_of(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.empty() || arg.find_first_of(" \t'\"") != std::string::npos) {
      std::string quoted = "'";
      for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      arg = quoted + "'";
    }
    if (i > 0) line += ' ';
    line += arg;
  }
  return line;
}

std::string origin_of(const Provenance& provenance) {
  if (!provenance.input.empty()) return provenance.input;
  if (provenance.parameters_json.empty() || provenance.parameters_json == "{}")
    return provenance.method;
  return fmt::format("{} {}", provenance.method, provenance.parameters_json);
}

}  // namespace tactile
