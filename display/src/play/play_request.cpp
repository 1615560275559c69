// The play request's option table and its rules; see play_request.hpp.

#include "tactile/display/play_request.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "tactile/display/latero_transport.hpp"

namespace tactile::display {

namespace rows = option_rows;

const std::vector<OptionRow<LateroBladeMapping>>& blade_mapping_options() {
  using R = LateroBladeMapping;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t = {
        rows::number<R>("blade_centre_raw", &R::centre_raw, 0, 255, "",
                        "Latero: raw blade value at rest"),
        rows::number<R>("blade_raw_per_unit", &R::raw_per_unit, -255, 255, "",
                        "Latero: raw units for a deflection of +full scale (negative: +x "
                        "lowers it)"),
        rows::number<R>("blade_max_raw", &R::max_raw, 1, 255, "",
                        "Latero: largest raw blade value sent"),
        // Blades move tens to hundreds of micrometres; far outside, every frame maps to rest
        // (too large) or to the clamp (too small) without a word.
        rows::number<R>("blade_full_scale_um", &R::full_scale_um, 0.1, 10000, "um",
                        "Latero: deflection that moves a blade by raw-per-unit"),
    };
    // A blade that never moves: every frame would play as rest.
    t[1].check_number = [](double v) {
      return v >= -255 && v <= 255 && v != 0
                 ? std::string()
                 : fmt::format("{} is out of range: must be from -255 to 255 and not 0", v);
    };
    return t;
  }();
  return table;
}

const std::vector<OptionRow<PlayRequest>>& play_options() {
  using R = PlayRequest;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t = {
        rows::positional_path<R>("movie", &R::movie, "MOVIE_H5", "Tactile movie (HDF5)"),
        rows::flag<R>("headless", &R::headless, "Play into the emulated device, no window"),
        rows::path<R>("preview", &R::preview, "Preview image (PNG) written when headless"),
        rows::number<R>("loops", &R::loops, 1, 1000000, "", "Times to play the movie"),
        rows::text<R>(
            "latero", &R::latero, "HOST[:PORT]",
            [](const std::string& text) {
              try {
                parse_latero_address(text);
              } catch (const std::invalid_argument& e) {
                return std::string(e.what());
              }
              return std::string();
            },
            "Play on the Latero at HOST[:PORT] (UDP, port 8900 by default)"),
    };
    rows::append_nested<R>(
        t, blade_mapping_options(), [](auto& r) -> auto& { return r.blade; },
        {"blade_centre_raw", "blade_raw_per_unit", "blade_max_raw", "blade_full_scale_um"});
    return t;
  }();
  return table;
}

ResolvedPlay resolve(const PlayRequest& request, OptionSpelling spelling, int stop_fd) {
  const auto label = [spelling](std::string_view name) { return option_label(name, spelling); };
  // The movie is the caller's (the command line's checked input, a Movie object).
  check_named_options(request, play_options(), spelling);
  if (request.latero && request.headless) {
    throw RequestError(fmt::format("{}: not with {}: a Latero plays on the Latero",
                                   label("headless"), label("latero")));
  }
  const LateroBladeMapping defaults;
  const LateroBladeMapping& b = request.blade;
  if (!request.latero &&
      (b.centre_raw != defaults.centre_raw || b.raw_per_unit != defaults.raw_per_unit ||
       b.max_raw != defaults.max_raw || b.full_scale_um != defaults.full_scale_um)) {
    throw RequestError(fmt::format("the blade mapping is only for a Latero: give {} HOST[:PORT]",
                                   label("latero")));
  }
  ResolvedPlay r;
  r.headless = request.headless;
  r.preview_png = request.preview.value_or(std::filesystem::path());
  r.loops = request.loops;
  r.stop_fd = stop_fd;
  if (request.latero) {
    try {
      validate_blade_mapping(b);
    } catch (const std::invalid_argument& e) {
      throw RequestError(e.what());
    }
    r.latero = LateroPlayTarget{*request.latero, b};
  }
  return r;
}

}  // namespace tactile::display
