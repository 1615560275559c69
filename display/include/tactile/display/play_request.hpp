#pragma once
// `play` as a request: where a movie plays (headless, a Latero) and how, its option table (read
// by the command line and the Python module alike) and resolve(), which applies the rules
// between the options and gives play_anywhere what it takes. Every default is a member
// initialiser here; the blade mapping's are LateroBladeMapping's (OpenLatero's).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tactile/common/option_table.hpp"
#include "tactile/display/latero_protocol.hpp"
#include "tactile/display/play_anywhere.hpp"

namespace tactile::display {

struct PlayRequest {
  std::filesystem::path movie;  // the command line's input (Python passes a Movie)
  bool headless = false;
  std::optional<std::string> latero;  // HOST[:PORT]; set: play there and nowhere else
  LateroBladeMapping blade;
  // Written when the movie plays headless; unset (Python's None): no preview.
  std::optional<std::filesystem::path> preview = std::filesystem::path("preview.png");
  int loops = 1;
};

const std::vector<OptionRow<PlayRequest>>& play_options();

// The blade mapping's rows alone, for the commands that take a blade mapping without playing a
// movie (`emulate --latero`, `live --latero`).
const std::vector<OptionRow<LateroBladeMapping>>& blade_mapping_options();

// Checks every value and the rules between them (RequestError in the front end's spelling):
// headless and latero exclude each other, a blade mapping only with latero and consistent
// (validate_blade_mapping). `stop_fd` is the front end's stop signal (ResolvedPlay::stop_fd).
ResolvedPlay resolve(const PlayRequest& request, OptionSpelling spelling, int stop_fd = -1);

}  // namespace tactile::display
