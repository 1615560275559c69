// The map request's option table and its rules; see map_request.hpp.

#include "tactile/mapping/map_request.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <stdexcept>

#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/limits.hpp"

namespace tactile::mapping {

namespace rows = option_rows;

std::string layout_name_problem(const std::string& name_or_path) {
  const auto& names = movie::kBuiltinLayoutNames;
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) return {};
  const std::filesystem::path path(name_or_path);
  if (path.extension() != ".json") {
    return fmt::format("unknown layout '{}' (known: {}, or a layout FILE.json)", name_or_path,
                       fmt::join(names, ", "));
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return fmt::format("no such layout file: {}", name_or_path);
  }
  return {};
}

const std::vector<OptionRow<MapRequest>>& map_options() {
  using R = MapRequest;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t = {
        rows::positional_path<R>("strain", &R::strain, "STRAIN_H5",
                                 "Strain movie (HDF5, from `tactile capture`)"),
        rows::path<R>("layout", &R::layout,
                      fmt::format("Contactor layout: {}, or a custom layout FILE.json (schema in "
                                  "docs/formats.md)",
                                  fmt::join(movie::kBuiltinLayoutNames, ", "))),
        rows::choice<R>(
            "method", [](auto& r) -> auto& { return r.params.method; }, kMappingMethodNames,
            "Mapping method. integrated: the deflection differences between\n"
            "neighbouring contactors reproduce the measured strain; proportional: each\n"
            "contactor deflects by its local strain, which does not impose that strain\n"
            "(correlation 0.02-0.05 on the ground-truth scenes); profile: from a surface\n"
            "profile (experiments only)"),
        rows::number<R>(
            "gain", [](auto& r) -> auto& { return r.params.gain_um_per_strain; }, 0.001, 1e6,
            "um per unit strain",
            "Deflection per unit strain (integrated: per mm of pitch, so 1000\n"
            "reproduces the skin's extension)"),
        rows::choice<R>(
            "normalise", [](auto& r) -> auto& { return r.params.normalisation; },
            kNormalisationNames,
            "none: gain as given; peak: scale so the largest deflection fills\n"
            "peak_fraction of the range; p99: the same with the 99th percentile"),
        rows::number<R>(
            "peak_fraction", [](auto& r) -> auto& { return r.params.peak_fraction; }, 0.001, 1.0,
            "", "Share of the deflection range that normalise fills"),
        rows::choice<R>(
            "strain_mode", [](auto& r) -> auto& { return r.params.strain; }, kStrainModeNames,
            "per-frame: the movie's strain frames as captured; accumulated: strain from\n"
            "the reference frame along the tracks (contactors follow the skin)"),
        rows::number<R>(
            "reference_frame", [](auto& r) -> auto& { return r.params.accumulate.reference_frame; },
            -1, 1e8, "", "Camera frame the accumulated strain starts from (-1: the first)"),
        rows::number<R>(
            "rate_hz", [](auto& r) -> auto& { return r.params.rate_hz; }, 1,
            movie::kMaxPlayableRateHz, "Hz",
            "Display frame rate, a whole number of hertz (default: the layout's own "
            "rate,\ne.g. stress 700 Hz, latero 750 Hz)"),
    };
    t[1].check_text = layout_name_problem;
    t[6].cli_alias = "--strain";
    // A rate the firmware can play, checked where the option is read so that the error names it.
    t[8].check_number = [](double v) {
      return movie::is_playable_rate(v)
                 ? std::string()
                 : fmt::format("{} is out of range: must be {}", v, movie::kPlayableRateRule);
    };
    return t;
  }();
  return table;
}

ResolvedMap resolve(const MapRequest& request, const movie::Layout& layout,
                    OptionSpelling spelling) {
  // The strain file and the layout's name are the caller's (the command line's input, a Layout
  // object): only the parameters are checked here.
  for (const auto& row : map_options()) {
    if (row.positional || row.name == "layout") continue;
    if (const std::string problem = option_problem(row, row.get(request)); !problem.empty()) {
      throw RequestError(fmt::format("{}: {}", option_label(row.name, spelling), problem));
    }
  }
  ResolvedMap r{layout, {}};
  try {
    r.params = resolve_mapping_params(request.params, layout);
  } catch (const RequestError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw RequestError(e.what());
  }
  return r;
}

void check_against_strain(const ResolvedMap& resolved, const capture::StrainMovie& strain,
                          const std::string& input, OptionSpelling spelling) {
  const auto& params = resolved.params;
  if (params.strain != StrainMode::accumulated || params.accumulate.reference_frame < 0) return;
  const std::int32_t last = last_reference_frame(strain);
  if (params.accumulate.reference_frame > last) {
    throw RequestError(fmt::format("{}: frame {} is not in {}, whose frames are 0 to {}",
                                   option_label("reference_frame", spelling),
                                   params.accumulate.reference_frame, input, last));
  }
}

ResolvedMap resolve(const MapRequest& request, OptionSpelling spelling) {
  if (const std::string problem = layout_name_problem(request.layout); !problem.empty()) {
    throw RequestError(fmt::format("{}: {}", option_label("layout", spelling), problem));
  }
  return resolve(request, movie::resolve_layout(request.layout), spelling);
}

}  // namespace tactile::mapping
