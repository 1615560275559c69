// Plays a small movie headless into the emulated device and writes its preview strip, with the
// display core alone: play_anywhere with no back ends.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "tactile/display/play_anywhere.hpp"
#include "tactile/movie/layout_json.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: display_consumer OUT_PREVIEW.png\n");
    return 2;
  }
  try {
    tactile::movie::TactileMovie movie;
    movie.layout = tactile::movie::resolve_layout("latero");
    movie.rate_hz = movie.layout.max_rate_hz;
    movie.frame_count = 20;
    const auto n = static_cast<std::size_t>(movie.layout.contactor_count());
    movie.deflection_um.assign(n * 20, 0.0f);
    movie.frame(10)[0] = 10.0f;
    tactile::display::ResolvedPlay request;
    request.preview_png = argv[1];
    const auto result = tactile::display::play_anywhere(
        movie, request, [](const std::string& text) { std::fputs(text.c_str(), stdout); }, {});
    const bool played = result.target == tactile::display::PlaybackTarget::headless &&
                        result.report && result.report->movie_frames == 20 &&
                        result.final_max_um == 0 && std::filesystem::file_size(argv[1]) > 0;
    return played ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "display_consumer: %s\n", e.what());
    return 1;
  }
}
