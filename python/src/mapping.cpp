// map(strain, layout, method=...): the mapping with the parameters `tactile map` takes, resolved
// by the same rules (mapping::resolve_mapping_params).

#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "movies.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/map.hpp"

namespace tactile::python {

namespace {

std::shared_ptr<movie::TactileMovie> map_strain(
    const capture::StrainMovie& strain, const LayoutArgument& layout_arg, const std::string& method,
    double gain_um_per_strain, const std::string& normalise, double peak_fraction,
    std::optional<double> rate_hz, const std::string& strain_mode, int reference_frame) {
  const movie::Layout layout = layout_argument(layout_arg);
  mapping::MappingParams params;
  params.method = mapping::parse_mapping_method(method);
  params.gain_um_per_strain = gain_um_per_strain;
  params.normalisation = mapping::parse_normalisation(normalise);
  params.peak_fraction = peak_fraction;
  params.rate_hz = rate_hz;
  params.strain = mapping::parse_strain_mode(strain_mode);
  params.accumulate.reference_frame = reference_frame;
  params.program_version = kVersion;
  // Before any work: fail fast on bad parameters, as `tactile map` does.
  mapping::resolve_mapping_params(params, layout);
  if (strain.frames.empty()) {
    throw std::invalid_argument("map: the strain movie has no strain frames");
  }
  py::gil_scoped_release unlocked;
  auto out =
      std::make_shared<movie::TactileMovie>(mapping::map_strain_movie(strain, layout, params));
  return out;
}

}  // namespace

void bind_mapping(py::module_& m) {
  m.def("map", &map_strain, py::arg("strain"), py::arg("layout") = "stress", py::kw_only(),
        py::arg("method") = "integrated", py::arg("gain_um_per_strain") = 1000.0,
        py::arg("normalise") = "none", py::arg("peak_fraction") = 1.0,
        py::arg("rate_hz") = py::none(), py::arg("strain_mode") = "per-frame",
        py::arg("reference_frame") = -1,
        "A tactile movie from a strain movie, as `tactile map`: layout a Layout, a built-in name\n"
        "or a FILE.json; method integrated, proportional (profile needs a surface profile and is\n"
        "for experiments); normalise none, peak or p99; rate_hz unset = the layout's own rate;\n"
        "strain_mode per-frame or accumulated (from reference_frame, -1 = the first).");
}

}  // namespace tactile::python
