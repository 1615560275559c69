#include "tactile/common/json.hpp"

#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "provenance_fields.hpp"

namespace tactile {

void JsonOrigin::fail(const std::string& what) const {
  throw FormatError(fmt::format("{}: {}", origin, what));
}

namespace {

// nlohmann's message without its "[json.exception.parse_error.101] " tag: the user reads where
// and why, not the library's error number.
std::string plain_message(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const auto tag_end = what.rfind("] ", what.find(' '));
  return what.starts_with("[json.exception.") && tag_end != std::string::npos
             ? what.substr(tag_end + 2)
             : what;
}

// Parses `text`, refusing a key written twice in one object: nlohmann keeps the last, so
// {"rows": 6, ..., "rows": 200} would silently be 200 rows.
nlohmann::json parse_strict(const JsonOrigin& at, const std::string& text) {
  std::vector<std::set<std::string>> keys;  // one per open object
  std::string repeated;
  const auto callback = [&](int /*depth*/, nlohmann::json::parse_event_t event,
                            nlohmann::json& parsed) {
    switch (event) {
      case nlohmann::json::parse_event_t::object_start:
        keys.emplace_back();
        break;
      case nlohmann::json::parse_event_t::object_end:
        if (!keys.empty()) keys.pop_back();
        break;
      case nlohmann::json::parse_event_t::key:
        if (!keys.empty() && !keys.back().insert(parsed.get<std::string>()).second &&
            repeated.empty()) {
          repeated = parsed.get<std::string>();
        }
        break;
      default:
        break;
    }
    return true;
  };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text, callback);
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers beyond a double
    at.fail(fmt::format("not valid JSON ({})", plain_message(e)));
  }
  if (!repeated.empty()) {
    at.fail(fmt::format("field '{}' appears twice in one object (which one is meant?)", repeated));
  }
  return j;
}

}  // namespace

nlohmann::json parse_json(const JsonOrigin& at, const std::string& text) {
  return parse_strict(at, text);
}

std::string read_json_text(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw FormatError(fmt::format("{}: cannot open {}", path.string(), what));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what) {
  const JsonOrigin at{path.string()};
  // A pipe or a device would block the read forever (a FIFO with no writer) or never end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    at.fail(
        fmt::format("cannot open {}: not a regular file (a folder, device, pipe or socket)", what));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) at.fail(fmt::format("cannot open {}", what));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) at.fail(fmt::format("cannot read {}", what));
  nlohmann::json j = parse_strict(at, text);
  if (!j.is_object()) at.fail("expected a JSON object");
  return j;
}

nlohmann::json read_json_of_format(const std::filesystem::path& path, const std::string& what,
                                   const std::string& format) {
  nlohmann::json j = read_json_object(path, what);
  const std::string where = path.string();
  if (json_field<std::string>(j, "format", where) != format) {
    throw FormatError(fmt::format("{}: 'format' is not {}", where, format));
  }
  return j;
}

void json_only_keys(const JsonOrigin& at, const nlohmann::json& j, const std::string& where,
                    const std::set<std::string>& known) {
  if (!j.is_object()) at.fail(fmt::format("{} must be a JSON object, got {}", where, j.dump()));
  for (const auto& [key, value] : j.items()) {
    if (!known.contains(key)) {
      at.fail(
          fmt::format("{}: unknown field '{}' (known: {})", where, key, fmt::join(known, ", ")));
    }
  }
}

const nlohmann::json& json_required(const JsonOrigin& at, const nlohmann::json& j, const char* key,
                                    const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) {
    at.fail(where.empty() ? fmt::format("missing field '{}'", key)
                          : fmt::format("{}: missing field '{}'", where, key));
  }
  return *it;
}

double json_number(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_number()) at.fail(fmt::format("'{}' must be a number, got {}", what, v.dump()));
  const double x = v.get<double>();
  if (!std::isfinite(x)) at.fail(fmt::format("'{}' is not finite", what));
  return x;
}

std::int64_t json_integer(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_number_integer()) {
    at.fail(fmt::format("'{}' must be an integer, got {}", what, v.dump()));
  }
  return v.get<std::int64_t>();
}

std::string json_string(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_string() || v.get<std::string>().empty()) {
    at.fail(fmt::format("'{}' must be a non-empty string, got {}", what, v.dump()));
  }
  return v.get<std::string>();
}

nlohmann::json provenance_json(const Provenance& provenance) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& f : kProvenanceFields) j[f.name] = provenance.*f.field;
  return j;
}

Provenance read_provenance_json(const JsonOrigin& at, const nlohmann::json& j,
                                const std::string& where) {
  std::set<std::string> known;
  for (const auto& f : kProvenanceFields) {
    known.insert(f.name);
    if (f.former_name != nullptr) known.insert(f.former_name);
  }
  json_only_keys(at, j, where, known);
  Provenance p;
  for (const auto& f : kProvenanceFields) {
    // The current key, else the former one, else empty.
    for (const char* key : {f.name, f.former_name}) {
      if (key != nullptr && j.contains(key)) {
        p.*f.field = json_field<std::string>(j, key, at.origin);
        break;
      }
    }
  }
  return p;
}

}  // namespace tactile
