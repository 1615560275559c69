// `import tactile`: the Python module (docs in README.md, "Python").

#include "bindings.hpp"
#include "tactile/common/version.hpp"

PYBIND11_MODULE(tactile, m) {
  namespace tp = tactile::python;
  m.doc() =
      "tactile-movies from Python: tactile movies and strain movies as NumPy arrays, layouts,\n"
      "mapping, playing, synthetic sequences, capture, experiments and the classifier; errors "
      "carry the "
      "`tactile` program's\n"
      "messages.";
  m.attr("__version__") = tactile::kVersion;
  // Built against Debian's NumPy for Debian's interpreter: say so when another interpreter, one
  // without NumPy, imports it (pybind11 would only say "initialization failed").
  try {
    pybind11::module_::import("numpy");
  } catch (pybind11::error_already_set&) {
    throw pybind11::import_error(
        "tactile needs NumPy; it was built for " TACTILE_PYTHON_EXECUTABLE
        " (Debian's python3 with python3-numpy): run it with that interpreter");
  }
  tp::bind_errors(m);
  tp::bind_movies(m);
  tp::bind_strain_movies(m);
  tp::bind_mapping(m);
  tp::bind_play(m);
  tp::bind_capture(m);
  tp::bind_classifier(m);
  tp::bind_exchange(m);
  tp::bind_live(m);
  tp::bind_synth(m);
  tp::bind_experiment(m);
}
