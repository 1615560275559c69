#pragma once
// Layout arguments as Python passes them: a Layout, a built-in name or a FILE.json.

#include <string>
#include <variant>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::python {

using LayoutArgument = std::variant<movie::Layout, std::string>;

movie::Layout layout_argument(const LayoutArgument& layout);

}  // namespace tactile::python
