#pragma once
// Custom contactor layouts from a small JSON file, so a lab can describe its own array without
// touching code. Schema (every field required; unknown fields are errors, so a typo is never
// silently ignored):
//   {
//     "name": "my-array",
//     "rows": 6, "cols": 6,
//     "pitch_mm": [1.0, 1.2],                 // [x, y] centre-to-centre spacing
//     "contactor_size_mm": [0.5, 0.8],        // [width, height] of a contactor tip
//     "deflection_axis": "x",                 // "x" or "y": the direction contactors move
//     "deflection_range_um": [-80, 80],       // [min, max]; must contain 0 (neutral)
//     "max_rate_hz": 1000
//   }

#include <filesystem>
#include <string>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

// Parses the JSON text of a layout. `where` names the source in messages (e.g. the file name).
// Throws tactile::FormatError naming the problem: not JSON, not an object, a missing or unknown
// field, a wrong type, a grid without contactors, non-positive or non-finite pitch, size or rate,
// contactors wider than their pitch, an axis other than x/y, a range that is empty or does not
// contain 0.
Layout parse_layout_json(const std::string& text, const std::string& where);

// Reads and parses a layout file; a missing or unreadable file is a FormatError too.
Layout read_layout_json(const std::filesystem::path& path);

// The layout in the schema above (parse_layout_json(layout_to_json(l)) == l).
std::string layout_to_json(const Layout& layout);

// A built-in layout by name (stress, stress2, latero), or, when `name_or_path` ends in ".json",
// the custom layout in that file.
Layout resolve_layout(const std::string& name_or_path);

}  // namespace tactile::movie
