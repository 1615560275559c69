// map(strain, layout, ...): the mapping `tactile map` makes, its keywords made from the map
// request's option table (mapping::map_options) and resolved by the same rules.

#include <memory>
#include <string>

#include "bindings.hpp"
#include "movies.hpp"
#include "request_kwargs.hpp"
#include "tactile/common/version.hpp"
#include "tactile/mapping/map_request.hpp"

namespace tactile::python {

namespace {

std::shared_ptr<movie::TactileMovie> map_strain(const capture::StrainMovie& strain,
                                                const LayoutArgument& layout_arg,
                                                const py::kwargs& kwargs) {
  mapping::MapRequest request;
  set_from_kwargs(request, mapping::map_options(), kwargs, "map");
  request.params.program_version = kVersion;
  // Before any work: fail fast on bad parameters, as `tactile map` does.
  const mapping::ResolvedMap resolved =
      mapping::resolve(request, layout_argument(layout_arg), OptionSpelling::python);
  if (strain.frames.empty()) {
    throw std::invalid_argument("map: the strain movie has no strain frames");
  }
  mapping::check_against_strain(resolved, strain, "the strain movie", OptionSpelling::python);
  py::gil_scoped_release unlocked;
  return std::make_shared<movie::TactileMovie>(
      mapping::map_strain_movie(strain, resolved.layout, resolved.params));
}

}  // namespace

void bind_mapping(py::module_& m) {
  def_with_kwargs(
      m, "map", &map_strain, mapping::map_options(),
      "A tactile movie from a strain movie, as `tactile map`: layout a Layout, a built-in name\n"
      "or a FILE.json. Keywords (the command line's options, with underscores):",
      py::arg("strain"), py::arg("layout") = "stress");
}

}  // namespace tactile::python
