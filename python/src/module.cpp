// `import tactile`: the Python module (docs in README.md, "Python").

#include "bindings.hpp"
#include "tactile/common/version.hpp"

PYBIND11_MODULE(tactile, m) {
  namespace tp = tactile::python;
  m.doc() =
      "tactile-movies from Python: tactile movies and strain movies as NumPy arrays, layouts,\n"
      "mapping, playing, capture and the classifier; errors carry the `tactile` program's\n"
      "messages.";
  m.attr("__version__") = tactile::kVersion;
  tp::bind_errors(m);
  tp::bind_movies(m);
  tp::bind_strain_movies(m);
  tp::bind_mapping(m);
  tp::bind_play(m);
  tp::bind_capture(m);
  tp::bind_classifier(m);
  tp::bind_exchange(m);
}
