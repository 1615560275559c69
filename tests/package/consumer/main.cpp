// Reads a strain movie, maps it onto the STReSS layout, writes the tactile movie and reads it
// back: the public API of three installed modules, linked through find_package(tactile).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer STRAIN.h5 OUT_MOVIE.h5\n");
    return 2;
  }
  try {
    const auto strain = tactile::capture::read_strain_movie(argv[1]);
    const auto layout = tactile::movie::resolve_layout("stress");
    tactile::mapping::MappingParams params;
    const auto movie = tactile::mapping::map_strain_movie(strain, layout, params);
    tactile::movie::write_tactile_movie(argv[2], movie);
    const auto back = tactile::movie::read_tactile_movie(argv[2]);
    std::printf("tactile %s: %zu strain frames -> %d movie frames at %g Hz\n", tactile::kVersion,
                strain.frames.size(), back.frame_count, back.rate_hz);
    return back.frame_count == movie.frame_count && back.frame_count > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
