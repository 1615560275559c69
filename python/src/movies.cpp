// Tactile movies and layouts. A Movie owns its C++ TactileMovie; `deflection_um` is a NumPy view
// of that movie's buffer (no copy: a 1 h movie at 700 Hz is read once, into the buffer the
// array shows), kept alive by the Movie it came from.

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <utility>
#include <variant>

#include "bindings.hpp"
#include "movies.hpp"
#include "tactile/common/error.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::python {

using movie::Layout;
using movie::TactileMovie;

movie::Layout layout_argument(const LayoutArgument& layout) {
  if (const auto* l = std::get_if<Layout>(&layout)) return *l;
  const std::string& name = std::get<std::string>(layout);
  return with_inputs({std::filesystem::path(name).extension() == ".json" ? name : ""},
                     [&] { return movie::resolve_layout(name); });
}

namespace {

std::string dtype_name(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

// Float32 deflections of shape (frames, rows, cols), copied once into the movie's own buffer.
std::vector<float> deflections_from(const py::array& a, const Layout& layout) {
  const char kind = a.dtype().kind();
  if (kind != 'f') {
    throw py::type_error(fmt::format(
        "deflection_um: dtype {} is not a floating-point type; pass float32 micrometres "
        "(frames, rows, cols)",
        dtype_name(a)));
  }
  if (a.ndim() != 3 || a.shape(1) != layout.rows || a.shape(2) != layout.cols) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i)
      shape += fmt::format("{}{}", i ? ", " : "", a.shape(i));
    throw std::invalid_argument(
        fmt::format("deflection_um: shape ({}) does not fit the layout {} ({} x {}): expected "
                    "(frames, {}, {})",
                    shape, layout.name, layout.rows, layout.cols, layout.rows, layout.cols));
  }
  const auto f32 = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  return {f32.data(), f32.data() + f32.size()};
}

Layout make_layout(std::string name, std::int32_t rows, std::int32_t cols, double pitch_x_mm,
                   double pitch_y_mm, double contactor_width_mm, double contactor_height_mm,
                   const std::string& axis, double deflection_min_um, double deflection_max_um,
                   double max_rate_hz) {
  Layout l;
  l.name = std::move(name);
  l.rows = rows;
  l.cols = cols;
  l.pitch_x_mm = pitch_x_mm;
  l.pitch_y_mm = pitch_y_mm;
  l.contactor_width_mm = contactor_width_mm;
  l.contactor_height_mm = contactor_height_mm;
  l.axis = parse_name("axis", axis, movie::kDeflectionAxisNames);
  l.deflection_min_um = deflection_min_um;
  l.deflection_max_um = deflection_max_um;
  l.max_rate_hz = max_rate_hz;
  // The checks of a layout file, so a layout made here is one a file could hold.
  try {
    return movie::parse_layout_json(movie::layout_to_json(l), "Layout");
  } catch (const FormatError& e) {
    throw std::invalid_argument(e.what());
  }
}

std::shared_ptr<TactileMovie> make_movie(const py::array& deflection_um,
                                         const LayoutArgument& layout_arg,
                                         std::optional<double> rate_hz,
                                         std::optional<movie::Provenance> provenance) {
  auto m = std::make_shared<TactileMovie>();
  m->layout = layout_argument(layout_arg);
  m->rate_hz = rate_hz.value_or(m->layout.max_rate_hz);
  m->deflection_um = deflections_from(deflection_um, m->layout);
  m->frame_count = static_cast<std::int32_t>(deflection_um.shape(0));
  if (provenance) m->provenance = *provenance;
  movie::validate_movie(*m);
  return m;
}

}  // namespace

void bind_movies(py::module_& m) {
  py::class_<Layout>(m, "Layout",
                     "Geometry and limits of a contactor array; contactor (row, col) rests at "
                     "(col * pitch_x_mm, row * pitch_y_mm).")
      .def(py::init(&make_layout), py::kw_only(), py::arg("name"), py::arg("rows"), py::arg("cols"),
           py::arg("pitch_x_mm") = 1.0, py::arg("pitch_y_mm") = 1.0,
           py::arg("contactor_width_mm") = 0.5, py::arg("contactor_height_mm") = 0.5,
           py::arg("axis") = "x", py::arg("deflection_min_um") = -50.0,
           py::arg("deflection_max_um") = 50.0, py::arg("max_rate_hz") = 700.0,
           "A custom layout, checked as a layout file is (ValueError naming the field).")
      .def_readonly("name", &Layout::name)
      .def_readonly("rows", &Layout::rows)
      .def_readonly("cols", &Layout::cols)
      .def_readonly("pitch_x_mm", &Layout::pitch_x_mm)
      .def_readonly("pitch_y_mm", &Layout::pitch_y_mm)
      .def_readonly("contactor_width_mm", &Layout::contactor_width_mm)
      .def_readonly("contactor_height_mm", &Layout::contactor_height_mm)
      .def_property_readonly("axis", [](const Layout& l) { return movie::to_string(l.axis); })
      .def_readonly("deflection_min_um", &Layout::deflection_min_um)
      .def_readonly("deflection_max_um", &Layout::deflection_max_um)
      .def_readonly("max_rate_hz", &Layout::max_rate_hz)
      .def_property_readonly("contactor_count", &Layout::contactor_count)
      .def("to_json", &movie::layout_to_json, "The layout in the layout-file schema.")
      .def("__repr__", [](const Layout& l) {
        return fmt::format("<tactile.Layout {} {} x {}, pitch {:g} x {:g} mm, {:g} Hz>", l.name,
                           l.rows, l.cols, l.pitch_x_mm, l.pitch_y_mm, l.max_rate_hz);
      });

  m.def("layout", &layout_argument, py::arg("name_or_path"),
        "A built-in layout (stress, stress2, latero) or the custom layout of a FILE.json.");
  m.def(
      "layout_from_json",
      [](const std::string& text) { return movie::parse_layout_json(text, "layout JSON"); },
      py::arg("text"), "A layout from its JSON text (schema in docs/formats.md).");

  py::class_<movie::Provenance>(m, "Provenance",
                                "How a movie was made (each field as in docs/formats.md).")
      .def(py::init<>())
      .def_readwrite("input", &movie::Provenance::input)
      .def_readwrite("program_version", &movie::Provenance::program_version)
      .def_readwrite("command_line", &movie::Provenance::command_line)
      .def_readwrite("method", &movie::Provenance::method)
      .def_readwrite("parameters_json", &movie::Provenance::parameters_json)
      .def_readwrite("created_utc", &movie::Provenance::created_utc);

  py::class_<TactileMovie, std::shared_ptr<TactileMovie>>(
      m, "Movie",
      "A tactile movie: frames of contactor deflections (micrometres) on a layout at rate_hz.")
      .def(py::init(&make_movie), py::arg("deflection_um"), py::arg("layout"),
           py::arg("rate_hz") = py::none(), py::arg("provenance") = py::none(),
           "From a (frames, rows, cols) array of deflections in micrometres (copied once to "
           "float32); rate_hz defaults to the layout's own rate.")
      .def_property_readonly(
          "deflection_um",
          [](py::object self) {
            auto& mv = self.cast<TactileMovie&>();
            const auto rows = static_cast<py::ssize_t>(mv.layout.rows);
            const auto cols = static_cast<py::ssize_t>(mv.layout.cols);
            const auto f = static_cast<py::ssize_t>(sizeof(float));
            // A view of the movie's own buffer; the array keeps the Movie alive.
            return py::array_t<float>({static_cast<py::ssize_t>(mv.frame_count), rows, cols},
                                      {rows * cols * f, cols * f, f}, mv.deflection_um.data(),
                                      self);
          },
          "(frames, rows, cols) float32 view of the movie's buffer (no copy; writes change the "
          "movie).")
      .def_readonly("layout", &TactileMovie::layout)
      .def_readonly("rate_hz", &TactileMovie::rate_hz)
      .def_readonly("frame_count", &TactileMovie::frame_count)
      .def_readwrite("provenance", &TactileMovie::provenance)
      .def_property_readonly("duration_s", &TactileMovie::duration_s)
      .def("__repr__", [](const TactileMovie& mv) {
        return fmt::format("<tactile.Movie {} frames of {} x {} ({}) at {:g} Hz, {:.3f} s>",
                           mv.frame_count, mv.layout.rows, mv.layout.cols, mv.layout.name,
                           mv.rate_hz, mv.duration_s());
      });

  def_reader<TactileMovie>(
      m, "read_movie", [](const auto& path) { return movie::read_tactile_movie(path); },
      "Reads a tactile movie (HDF5, docs/formats.md).");
  def_writer<TactileMovie>(m, "write_movie", movie::write_tactile_movie,
                           "Writes a tactile movie as HDF5, atomically.");
  def_writer<TactileMovie>(m, "export_csv", movie::export_tactile_csv,
                           "One CSV row per frame: frame,t_s,r0c0_um,...");
}

}  // namespace tactile::python
