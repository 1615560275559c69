#include "tactile/common/provenance.hpp"

#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <utility>

#include "tactile/common/version.hpp"
#include "utc_now.hpp"

namespace tactile {

Provenance make_provenance(std::string input, std::string method, std::string parameters_json) {
  Provenance p;
  p.input = std::move(input);
  p.program_version = kVersion;
  p.method = std::move(method);
  p.parameters_json = std::move(parameters_json);
  p.created_utc = utc_now_iso8601();
  return p;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
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
