#include "tactile/common/provenance.hpp"

#include <fmt/format.h>

#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string_view>
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
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  // The reproducible-builds convention: a fixed creation time, so that the same work written
  // twice (a movie saved by the authoring window and its experiment re-run) gives equal files.
  if (const char* fixed = std::getenv("SOURCE_DATE_EPOCH"); fixed != nullptr) {
    const std::string_view text(fixed);
    std::int64_t seconds = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seconds);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || seconds < 0 ||
        seconds >
            253402300799) {  // 9999-12-31T23:59:59Z, the last time ISO 8601 writes in 4 digits
      throw std::invalid_argument(
          fmt::format("SOURCE_DATE_EPOCH='{}' is not a time: must be whole seconds since 1970 UTC, "
                      "from 0 to 253402300799",
                      text));
    }
    now = static_cast<std::time_t>(seconds);
  }
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
