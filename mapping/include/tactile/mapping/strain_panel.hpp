#pragma once
// The viewer's side panel from a strain movie: its Delaunay edges with their relative length
// change, in movie time. Lives in mapping, which already joins capture's strain to display's
// types, because display knows nothing of strain.

#include <filesystem>
#include <optional>
#include <string>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/movie/side_field.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// Each strain frame becomes a field frame: every edge between its two points at the end of
// the frame pair, valued by rel_change, shown from the frame's time relative to the first
// frame's (the tactile movie's time 0, as mapping::resample starts there). Full scale as in
// capture's strain maps (99th percentile of |rel_change|). Throws std::invalid_argument for a
// strain movie without frames or edges, or with an edge naming a point the frame lacks.
movie::SideField strain_side_field(const capture::StrainMovie& strain, const std::string& title);

// The strain movie to show beside `movie`: `explicit_path` when given (it must be a readable
// strain movie), else the movie's provenance source when that names an existing strain movie
// file (as given, then beside the movie file); nothing otherwise.
std::optional<std::filesystem::path> find_source_strain(const movie::TactileMovie& movie,
                                                        const std::filesystem::path& movie_path,
                                                        const std::filesystem::path& explicit_path);

}  // namespace tactile::mapping
