// Writes a small tactile movie on a built-in layout and reads it back, with the movie library
// alone.
#include <cstdio>
#include <exception>

#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: movie_consumer OUT_MOVIE.h5\n");
    return 2;
  }
  try {
    tactile::movie::TactileMovie movie;
    movie.layout = tactile::movie::resolve_layout("latero");
    movie.rate_hz = movie.layout.max_rate_hz;
    movie.frame_count = 3;
    const auto n = static_cast<std::size_t>(movie.layout.contactor_count());
    movie.deflection_um.assign(n * 3, 0.0f);
    movie.frame(1)[0] = 10.0f;  // one contactor out and back: a value the read must keep
    tactile::movie::write_tactile_movie(argv[1], movie);
    const auto back = tactile::movie::read_tactile_movie(argv[1]);
    std::printf("%s: %d frames at %g Hz\n", back.layout.name.c_str(), back.frame_count,
                back.rate_hz);
    const bool same = back.layout.name == "latero" && back.frame_count == 3 &&
                      back.deflection_um == movie.deflection_um;
    return same ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "movie_consumer: %s\n", e.what());
    return 1;
  }
}
