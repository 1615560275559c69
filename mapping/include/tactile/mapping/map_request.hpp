#pragma once
// `map` as a request: the strain movie, the layout and the mapping's parameters, its option
// table (read by the command line, the Python module and the authoring window alike) and
// resolve(), which turns the layout's name into the layout and applies
// resolve_mapping_params. The defaults are MappingParams' own.

#include <filesystem>
#include <string>
#include <vector>

#include "tactile/common/option_table.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

struct MapRequest {
  std::filesystem::path strain;  // the strain movie's file (the command line's input)
  std::string layout = std::string(movie::kBuiltinLayoutNames[0]);  // a built-in name or FILE.json
  MappingParams params;
};

const std::vector<OptionRow<MapRequest>>& map_options();

// What is wrong with `name_or_path` as a layout (empty: nothing): neither a built-in name nor a
// .json file, or a .json file that does not exist.
std::string layout_name_problem(const std::string& name_or_path);

struct ResolvedMap {
  movie::Layout layout;
  MappingParams params;  // resolve_mapping_params's: rate_hz set
};

// The layout read (FormatError naming a bad layout file) and the parameters resolved; a
// parameter the mapping refuses is a RequestError in the front end's spelling.
ResolvedMap resolve(const MapRequest& request, OptionSpelling spelling);
// The same for a layout already made (Python's Layout objects, the authoring window).
ResolvedMap resolve(const MapRequest& request, const movie::Layout& layout,
                    OptionSpelling spelling);

// What the parameters ask of the strain movie itself, checked before any mapping: an
// accumulated strain's reference frame must be one of its frames. A RequestError naming the
// option and `input` (the strain movie's name for a person).
void check_against_strain(const ResolvedMap& resolved, const capture::StrainMovie& strain,
                          const std::string& input, OptionSpelling spelling);

}  // namespace tactile::mapping
