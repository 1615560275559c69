// Strain movies: tracked points, Delaunay edges and triangles as NumPy structured arrays that
// view the movie's own vectors (no copy), and strain movies made from such arrays.

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/strain_movie_io.hpp"

namespace tactile::python {

using capture::StrainEdge;
using capture::StrainFrame;
using capture::StrainMovie;
using capture::StrainTriangle;
using capture::TrackedPoint;

namespace {

struct Field {
  const char* name;
  const char* format;
  std::size_t offset;
};

py::dtype structured(std::initializer_list<Field> fields, std::size_t itemsize) {
  py::list names, formats, offsets;
  for (const auto& f : fields) {
    names.append(f.name);
    formats.append(f.format);
    offsets.append(f.offset);
  }
  return py::dtype(names, formats, offsets, static_cast<py::ssize_t>(itemsize));
}

// The C++ structs' own memory layout, so arrays of them are views.
py::dtype point_dtype() {
  return structured({{"track_id", "<i4", offsetof(TrackedPoint, track_id)},
                     {"frame", "<i4", offsetof(TrackedPoint, frame)},
                     {"type", "u1", offsetof(TrackedPoint, type)},
                     {"x_px", "<f8", offsetof(TrackedPoint, x_px)},
                     {"y_px", "<f8", offsetof(TrackedPoint, y_px)},
                     {"x_mm", "<f8", offsetof(TrackedPoint, x_mm)},
                     {"y_mm", "<f8", offsetof(TrackedPoint, y_mm)}},
                    sizeof(TrackedPoint));
}

py::dtype edge_dtype() {
  return structured({{"track_a", "<i4", offsetof(StrainEdge, track_a)},
                     {"track_b", "<i4", offsetof(StrainEdge, track_b)},
                     {"length_from_mm", "<f8", offsetof(StrainEdge, length_from_mm)},
                     {"length_to_mm", "<f8", offsetof(StrainEdge, length_to_mm)},
                     {"rel_change", "<f8", offsetof(StrainEdge, rel_change)}},
                    sizeof(StrainEdge));
}

template <typename T>
py::array view(const py::dtype& dtype, std::vector<T>& values, py::handle owner) {
  return py::array(dtype, {static_cast<py::ssize_t>(values.size())},
                   {static_cast<py::ssize_t>(sizeof(T))}, values.data(), owner);
}

py::array triangles_view(std::vector<StrainTriangle>& t, py::handle owner) {
  static_assert(sizeof(StrainTriangle) == 3 * sizeof(std::int32_t));
  return py::array_t<std::int32_t>(
      {static_cast<py::ssize_t>(t.size()), py::ssize_t{3}},
      {static_cast<py::ssize_t>(sizeof(StrainTriangle)), py::ssize_t{sizeof(std::int32_t)}},
      t.empty() ? nullptr : t.front().point_index.data(), owner);
}

// One field of a structured array as a 1-D array of T; names the argument and the field.
template <typename T>
py::array_t<T> column(const py::array& a, const char* field, const char* what) {
  if (!a.dtype().attr("names").is_none()) {
    const auto names = a.dtype().attr("names").cast<std::vector<std::string>>();
    if (std::find(names.begin(), names.end(), field) != names.end()) {
      if (a.ndim() != 1) {
        throw std::invalid_argument(
            fmt::format("{}: must be 1-D, has {} dimensions", what, a.ndim()));
      }
      const py::object values = a[field];
      return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(values);
    }
  }
  throw py::type_error(fmt::format("{}: dtype {} has no field '{}'; use tactile.{}", what,
                                   py::str(a.dtype()).cast<std::string>(), field,
                                   std::string_view(what).find("edge") != std::string_view::npos
                                       ? "EDGE_DTYPE"
                                       : "POINT_DTYPE"));
}

std::vector<TrackedPoint> points_from_array(const py::array& a, const char* what) {
  const auto id = column<std::int32_t>(a, "track_id", what);
  const auto frame = column<std::int32_t>(a, "frame", what);
  const auto type = column<std::uint8_t>(a, "type", what);
  const auto xp = column<double>(a, "x_px", what), yp = column<double>(a, "y_px", what);
  const auto xm = column<double>(a, "x_mm", what), ym = column<double>(a, "y_mm", what);
  std::vector<TrackedPoint> out(static_cast<std::size_t>(a.size()));
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    if (type.at(i) > 2) {
      throw std::invalid_argument(fmt::format(
          "{}[{}]: type {} is not 0 (pore), 1 (ending) or 2 (bifurcation)", what, i, type.at(i)));
    }
    out[static_cast<std::size_t>(i)] = {
        id.at(i), frame.at(i), static_cast<capture::FeatureType>(type.at(i)), xp.at(i), yp.at(i),
        xm.at(i), ym.at(i)};
  }
  return out;
}

std::vector<StrainEdge> edges_from_array(const py::array& a) {
  const char* what = "edges";
  const auto ta = column<std::int32_t>(a, "track_a", what);
  const auto tb = column<std::int32_t>(a, "track_b", what);
  const auto lf = column<double>(a, "length_from_mm", what);
  const auto lt = column<double>(a, "length_to_mm", what);
  const auto rc = column<double>(a, "rel_change", what);
  std::vector<StrainEdge> out(static_cast<std::size_t>(a.size()));
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    out[static_cast<std::size_t>(i)] = {ta.at(i), tb.at(i), lf.at(i), lt.at(i), rc.at(i)};
  }
  return out;
}

StrainFrame make_frame(std::int32_t frame_from, std::int32_t frame_to, double t_s,
                       const py::array& points_from, const py::array& points_to,
                       const py::array& edges, const py::array& triangles) {
  StrainFrame f;
  f.frame_from = frame_from;
  f.frame_to = frame_to;
  f.t_s = t_s;
  f.points_from = points_from_array(points_from, "points_from");
  f.points_to = points_from_array(points_to, "points_to");
  if (f.points_from.size() != f.points_to.size()) {
    throw std::invalid_argument(fmt::format(
        "points_to: {} points but points_from has {}; both hold the same tracks in the same order",
        f.points_to.size(), f.points_from.size()));
  }
  f.edges = edges_from_array(edges);
  if (triangles.dtype().kind() != 'i' && triangles.dtype().kind() != 'u') {
    throw py::type_error(fmt::format("triangles: dtype {} is not an integer type",
                                     py::str(triangles.dtype()).cast<std::string>()));
  }
  if (triangles.ndim() != 2 || triangles.shape(1) != 3) {
    throw std::invalid_argument("triangles: must have shape (n, 3): indices into points_from");
  }
  const auto t =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(triangles);
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    StrainTriangle tri;
    for (py::ssize_t k = 0; k < 3; ++k) {
      const std::int64_t index = t.at(i, k);
      if (index < 0 || index >= static_cast<std::int64_t>(f.points_from.size())) {
        throw std::invalid_argument(
            fmt::format("triangles[{}]: point index {} is out of range: must be 0 to {}", i, index,
                        static_cast<std::int64_t>(f.points_from.size()) - 1));
      }
      tri.point_index[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(index);
    }
    f.triangles.push_back(tri);
  }
  return f;
}

std::shared_ptr<StrainMovie> make_strain_movie(
    double frame_rate_hz, const py::array& tracks, std::vector<StrainFrame> frames,
    std::int32_t span_frames, std::optional<std::int32_t> camera_frame_count, double field_width_mm,
    double field_height_mm, std::optional<capture::Calibration> calibration, std::string source) {
  if (!(frame_rate_hz > 0)) {
    throw std::invalid_argument(
        fmt::format("frame_rate_hz: {} is out of range: must be > 0", frame_rate_hz));
  }
  if (span_frames < 1) {
    throw std::invalid_argument(
        fmt::format("span_frames: {} is out of range: must be >= 1", span_frames));
  }
  auto m = std::make_shared<StrainMovie>();
  m->frame_rate_hz = frame_rate_hz;
  m->span_frames = span_frames;
  m->tracks = points_from_array(tracks, "tracks");
  m->frames = std::move(frames);
  std::int32_t last = -1;
  for (const auto& p : m->tracks) last = std::max(last, p.frame);
  for (const auto& f : m->frames) last = std::max(last, f.frame_to);
  m->camera_frame_count = camera_frame_count.value_or(last + 1);
  m->field_width_mm = field_width_mm;
  m->field_height_mm = field_height_mm;
  if (calibration) m->calibration = *calibration;
  m->provenance = make_provenance(std::move(source), "built from arrays in Python");
  return m;
}

}  // namespace

void bind_strain_movies(py::module_& m) {
  m.attr("POINT_DTYPE") = point_dtype();
  m.attr("EDGE_DTYPE") = edge_dtype();

  py::class_<capture::Calibration>(m, "Calibration", "Pixel-to-millimetre mapping of a camera.")
      .def(py::init<>())
      .def_static("uniform", &capture::uniform_calibration, py::arg("px_per_mm"),
                  py::arg("width_px"), py::arg("height_px"))
      .def_property_readonly("px_to_mm",
                             [](const capture::Calibration& c) {
                               py::array_t<double> h(std::vector<py::ssize_t>{3, 3});
                               std::copy(c.px_to_mm.begin(), c.px_to_mm.end(), h.mutable_data());
                               return h;
                             })
      .def_readonly("mm_per_px", &capture::Calibration::mm_per_px)
      .def_readonly("image_width_px", &capture::Calibration::image_width_px)
      .def_readonly("image_height_px", &capture::Calibration::image_height_px)
      .def_readonly("method", &capture::Calibration::method);

  py::class_<StrainFrame>(m, "StrainFrame",
                          "Strain between camera frames frame_from and frame_to: the tracked "
                          "points at both ends, Delaunay edges and triangles.")
      .def(py::init(&make_frame), py::kw_only(), py::arg("frame_from"), py::arg("frame_to"),
           py::arg("t_s"), py::arg("points_from"), py::arg("points_to"), py::arg("edges"),
           py::arg("triangles"),
           "From structured arrays (tactile.POINT_DTYPE, tactile.EDGE_DTYPE) and an (n, 3) "
           "integer array of indices into points_from.")
      .def_readonly("frame_from", &StrainFrame::frame_from)
      .def_readonly("frame_to", &StrainFrame::frame_to)
      .def_readonly("t_s", &StrainFrame::t_s)
      .def_property_readonly("points_from",
                             [](py::object self) {
                               return view(point_dtype(), self.cast<StrainFrame&>().points_from,
                                           self);
                             })
      .def_property_readonly("points_to",
                             [](py::object self) {
                               return view(point_dtype(), self.cast<StrainFrame&>().points_to,
                                           self);
                             })
      .def_property_readonly(
          "edges",
          [](py::object self) { return view(edge_dtype(), self.cast<StrainFrame&>().edges, self); })
      .def_property_readonly("triangles", [](py::object self) {
        return triangles_view(self.cast<StrainFrame&>().triangles, self);
      });

  py::class_<StrainMovie, std::shared_ptr<StrainMovie>>(
      m, "StrainMovie", "Skin strain measured by capture: tracks, and strain frames.")
      .def(py::init(&make_strain_movie), py::kw_only(), py::arg("frame_rate_hz"), py::arg("tracks"),
           py::arg("frames"), py::arg("span_frames") = 1,
           py::arg("camera_frame_count") = py::none(), py::arg("field_width_mm") = 0.0,
           py::arg("field_height_mm") = 0.0, py::arg("calibration") = py::none(),
           py::arg("source") = "")
      .def_readonly("frame_rate_hz", &StrainMovie::frame_rate_hz)
      .def_readonly("span_frames", &StrainMovie::span_frames)
      .def_readonly("camera_frame_count", &StrainMovie::camera_frame_count)
      .def_readonly("field_width_mm", &StrainMovie::field_width_mm)
      .def_readonly("field_height_mm", &StrainMovie::field_height_mm)
      .def_readonly("calibration", &StrainMovie::calibration)
      .def_readwrite("provenance", &StrainMovie::provenance)
      .def_property_readonly(
          "tracks",
          [](py::object self) {
            return view(point_dtype(), self.cast<StrainMovie&>().tracks, self);
          },
          "Every kept track's points (tactile.POINT_DTYPE), a view of the movie's buffer.")
      .def_property_readonly(
          "frames",
          [](py::object self) {
            py::list out;
            for (auto& f : self.cast<StrainMovie&>().frames) {
              out.append(py::cast(&f, py::return_value_policy::reference_internal, self));
            }
            return out;
          },
          "The strain frames, each viewing the movie's buffers.")
      .def_property_readonly(
          "contact",
          [](py::object self) -> py::object {
            auto& c = self.cast<StrainMovie&>().contact;
            if (!c.measured()) return py::none();
            const std::vector<py::ssize_t> shape{c.frame_count(), c.grid.rows, c.grid.columns};
            py::dict d;
            d["cell_px"] = c.grid.cell_px;
            d["in_contact"] = py::array_t<std::uint8_t>(shape, c.in_contact.data(), self);
            d["ridge_contrast"] = py::array_t<double>(shape, c.ridge_contrast.data(), self);
            const std::vector<py::ssize_t> frames{c.frame_count()};
            if (c.per_frame()) {
              d["threshold"] = py::array_t<double>(frames, c.frame_threshold.data(), self);
              d["seen"] = py::array_t<std::uint8_t>(frames, c.frame_seen.data(), self);
            } else {
              d["threshold"] = c.threshold;
            }
            return d;
          },
          "Where the skin touched in each camera frame, or None (a movie made in Python, or a "
          "file written without it): a dict of cell_px, threshold (grey levels), in_contact "
          "(uint8, camera frames x rows x columns, 1 = touching) and ridge_contrast (the same "
          "shape, grey levels), viewing the movie's buffers. A live recording's map judged each "
          "frame as it came: its threshold is then one per camera frame, and `seen` (uint8, one "
          "per camera frame) is 0 for a frame the session dropped unseen (its cells say nothing).")
      .def("__repr__", [](const StrainMovie& s) {
        return fmt::format("<tactile.StrainMovie {} camera frames at {:g} Hz, {} strain frames>",
                           s.camera_frame_count, s.frame_rate_hz, s.frames.size());
      });

  def_reader<StrainMovie>(
      m, "read_strain_movie", [](const auto& path) { return capture::read_strain_movie(path); },
      "Reads a strain movie (HDF5, docs/formats.md).");
  def_writer<StrainMovie>(m, "write_strain_movie", capture::write_strain_movie,
                          "Writes a strain movie as HDF5, atomically.");
}

}  // namespace tactile::python
