// HDF5 reading/writing and CSV export of tactile movies; schema in display/FORMAT.md.
#include "tactile/movie/movie_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/value_checks.hpp"

namespace tactile::movie {
namespace {

constexpr const char* kFormatName = "tactile-movie";
constexpr const char* kDataset = "deflection_um";

void write_layout(H5::H5File& file, const Layout& l) {
  h5::write_attr(file, "layout_name", l.name);
  h5::write_attr(file, "layout_rows", std::int64_t{l.rows});
  h5::write_attr(file, "layout_cols", std::int64_t{l.cols});
  h5::write_attr(file, "layout_pitch_x_mm", l.pitch_x_mm);
  h5::write_attr(file, "layout_pitch_y_mm", l.pitch_y_mm);
  h5::write_attr(file, "layout_contactor_width_mm", l.contactor_width_mm);
  h5::write_attr(file, "layout_contactor_height_mm", l.contactor_height_mm);
  h5::write_attr(file, "layout_axis", l.axis == DeflectionAxis::x ? "x" : "y");
  h5::write_attr(file, "layout_deflection_min_um", l.deflection_min_um);
  h5::write_attr(file, "layout_deflection_max_um", l.deflection_max_um);
  h5::write_attr(file, "layout_max_rate_hz", l.max_rate_hz);
}

Layout read_layout(const H5::H5File& file, const std::string& where) {
  Layout l;
  l.name = h5::read_attr_string(file, "layout_name", where);
  const auto rows = h5::read_attr_int(file, "layout_rows", where);
  const auto cols = h5::read_attr_int(file, "layout_cols", where);
  // Bounded so that rows * cols cannot overflow and a damaged header cannot ask for gigabytes.
  if (rows <= 0 || cols <= 0 || rows > 4096 || cols > 4096) {
    throw FormatError(fmt::format("{}: layout_rows x layout_cols = {} x {} is not a valid grid",
                                  where, rows, cols));
  }
  l.rows = static_cast<std::int32_t>(rows);
  l.cols = static_cast<std::int32_t>(cols);
  // Sizes and ranges no display could have are damage: say which, rather than play them.
  const auto size_mm = [&](const char* name) {
    return checks::in_range(h5::read_attr_double(file, name, where), kMinLayoutSizeMm,
                            kMaxLayoutSizeMm, where, name);
  };
  l.pitch_x_mm = size_mm("layout_pitch_x_mm");
  l.pitch_y_mm = size_mm("layout_pitch_y_mm");
  l.contactor_width_mm = size_mm("layout_contactor_width_mm");
  l.contactor_height_mm = size_mm("layout_contactor_height_mm");
  const std::string axis = h5::read_attr_string(file, "layout_axis", where);
  if (axis != "x" && axis != "y") {
    throw FormatError(fmt::format("{}: layout_axis is '{}', expected 'x' or 'y'", where, axis));
  }
  l.axis = axis == "x" ? DeflectionAxis::x : DeflectionAxis::y;
  l.deflection_min_um =
      checks::in_range(h5::read_attr_double(file, "layout_deflection_min_um", where), -1e6, 1e6,
                       where, "layout_deflection_min_um");
  l.deflection_max_um =
      checks::in_range(h5::read_attr_double(file, "layout_deflection_max_um", where), -1e6, 1e6,
                       where, "layout_deflection_max_um");
  if (!(l.deflection_min_um < l.deflection_max_um)) {
    throw FormatError(
        fmt::format("{}: layout_deflection_min_um {} must be below layout_deflection_max_um {}",
                    where, l.deflection_min_um, l.deflection_max_um));
  }
  // As in a layout file: rest (0) is where every contactor starts and is parked.
  if (!(l.deflection_min_um <= 0 && l.deflection_max_um >= 0)) {
    throw FormatError(fmt::format(
        "{}: layout deflection range [{}, {}] um does not contain 0 (the rest position)", where,
        l.deflection_min_um, l.deflection_max_um));
  }
  l.max_rate_hz = checks::in_range(h5::read_attr_double(file, "layout_max_rate_hz", where), 1,
                                   kMaxMovieRateHz, where, "layout_max_rate_hz");
  return l;
}

// A display clips a deflection a little beyond its layout's range (the saturation a movie's
// summary counts); one beyond it by more than the range's whole width is no contactor's
// position but damage or a unit mix-up (mm for um), refused naming where it is.
void check_deflections_in_reach(const TactileMovie& movie, const std::string& where) {
  const Layout& l = movie.layout;
  const double width = l.deflection_max_um - l.deflection_min_um;
  const double lo = l.deflection_min_um - width;
  const double hi = l.deflection_max_um + width;
  const auto per_frame = static_cast<std::size_t>(l.contactor_count());
  const auto cols = static_cast<std::size_t>(l.cols);
  for (std::size_t i = 0; i < movie.deflection_um.size(); ++i) {
    const double v = movie.deflection_um[i];
    if (v >= lo && v <= hi) continue;
    const std::size_t k = i % per_frame;
    throw FormatError(fmt::format(
        "{}/{}: frame {}, row {}, col {}: deflection {} um is out of range: layout '{}' moves "
        "from {} to {} um, and a movie's values may go beyond that by at most its width ({} to "
        "{} um)",
        where, kDataset, i / per_frame, k / cols, k % cols, v, l.name, l.deflection_min_um,
        l.deflection_max_um, lo, hi));
  }
}

}  // namespace

namespace {

// Everything but the deflections.
void write_header(H5::H5File& file, const TactileMovie& movie) {
  h5::write_attr(file, "format", kFormatName);
  h5::write_attr(file, "format_version", std::int64_t{kTactileMovieFormatVersion});
  h5::write_attr(file, "rate_hz", movie.rate_hz);
  h5::write_attr(file, "frame_count", std::int64_t{movie.frame_count});
  h5::write_attr(file, "units", "um");
  write_layout(file, movie.layout);
  h5::write_provenance(file, movie.provenance);
}

}  // namespace

void write_tactile_movie(const std::filesystem::path& path, const TactileMovie& movie) {
  validate_movie(movie);
  h5::write_file_atomically(path, [&](H5::H5File& file) {
    write_header(file, movie);
    h5::write_dataset(
        file, kDataset, movie.deflection_um,
        {static_cast<hsize_t>(movie.frame_count), static_cast<hsize_t>(movie.layout.rows),
         static_cast<hsize_t>(movie.layout.cols)});
  });
}

TactileMovieAppender::TactileMovieAppender(const std::filesystem::path& path,
                                           const TactileMovie& header)
    : file_(path),
      frame_size_(static_cast<std::size_t>(header.layout.rows) *
                  static_cast<std::size_t>(header.layout.cols)) {
  TactileMovie empty = header;
  empty.frame_count = 0;
  empty.deflection_um.clear();
  validate_movie(empty);
  try {
    write_header(file_.file(), empty);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), e.getDetailMsg()));
  }
  file_.create_rows(
      kDataset,
      {static_cast<hsize_t>(header.layout.rows), static_cast<hsize_t>(header.layout.cols)},
      std::vector<float>{});
  file_.start();
}

void TactileMovieAppender::append(const std::vector<float>& deflection_um) {
  if (deflection_um.size() != frame_size_) {
    throw std::invalid_argument(fmt::format("a frame of {} deflections for a layout of {}",
                                            deflection_um.size(), frame_size_));
  }
  pending_.insert(pending_.end(), deflection_um.begin(), deflection_um.end());
  ++frames_;
}

void TactileMovieAppender::flush() {
  file_.append(kDataset, pending_);
  pending_.clear();
  file_.set_attr("/", "frame_count", frames_);
  file_.flush();
}

void TactileMovieAppender::close() {
  flush();
  file_.close();
}

namespace {

TactileMovie read_checked(const std::filesystem::path& path) {
  bool unfinished = false;
  H5::H5File file = h5::open_for_reading(path, &unfinished);
  const std::string where = path.string();
  if (!h5::has_attr(file, "format")) {
    throw FormatError(fmt::format("{}: attribute 'format' is missing; not a tactile movie", where));
  }
  const std::string format = h5::read_attr_string(file, "format", where);
  if (format != kFormatName) {
    throw FormatError(fmt::format("{}: format is '{}', expected '{}'", where, format, kFormatName));
  }
  const auto version = h5::read_attr_int(file, "format_version", where);
  if (version < 1 || version > kTactileMovieFormatVersion) {
    throw FormatError(
        fmt::format("{}: format_version {} is not supported (this program reads 1..{})", where,
                    version, kTactileMovieFormatVersion));
  }
  const std::string units = h5::read_attr_string(file, "units", where);
  if (units != "um") {
    throw FormatError(fmt::format("{}: units is '{}', expected 'um'", where, units));
  }

  TactileMovie movie;
  movie.rate_hz = checks::in_range(h5::read_attr_double(file, "rate_hz", where), 1, kMaxMovieRateHz,
                                   where, "rate_hz");
  movie.layout = read_layout(file, where);
  // Checked before the dataset is read, whose shape is then checked against memory.
  auto frames =
      checks::int_in_range(h5::read_attr_int(file, "frame_count", where), 0,
                           std::numeric_limits<std::int32_t>::max(), where, "frame_count");

  std::vector<hsize_t> dims;
  movie.deflection_um = h5::read_floats(file, kDataset, 3, dims, where);
  if (unfinished) {
    // Its writer was killed (TactileMovieAppender): the frames and their count reach the disk
    // in either order, so only the frames both say are there are read.
    frames = std::min<std::int64_t>(frames, static_cast<std::int64_t>(dims[0]));
    dims[0] = static_cast<hsize_t>(frames);
    movie.deflection_um.resize(static_cast<std::size_t>(frames) * dims[1] * dims[2]);
  }
  if (dims[0] != static_cast<hsize_t>(frames)) {
    throw FormatError(fmt::format("{}/{}: has {} frames but frame_count says {}", where, kDataset,
                                  dims[0], frames));
  }
  if (dims[1] != static_cast<hsize_t>(movie.layout.rows) ||
      dims[2] != static_cast<hsize_t>(movie.layout.cols)) {
    throw FormatError(fmt::format("{}/{}: frames are {} x {} but the layout is {} x {}", where,
                                  kDataset, dims[1], dims[2], movie.layout.rows,
                                  movie.layout.cols));
  }
  movie.frame_count = static_cast<std::int32_t>(frames);
  movie.provenance = h5::read_provenance(file, where);
  try {
    validate_movie(movie);  // NaN values and layout ranges
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", where, e.what()));
  }
  check_deflections_in_reach(movie, where);
  return movie;
}

}  // namespace

TactileMovie read_tactile_movie(const std::filesystem::path& path, h5::ReadingProcess* process) {
  return h5::read_guarded<&read_checked>(path, "a tactile movie", process);
}

void export_tactile_csv(const std::filesystem::path& csv_path, const TactileMovie& movie) {
  validate_movie(movie);
  std::string header = "frame,t_s";
  for (std::int32_t r = 0; r < movie.layout.rows; ++r) {
    for (std::int32_t c = 0; c < movie.layout.cols; ++c) header += fmt::format(",r{}c{}_um", r, c);
  }
  auto out = csv::open_with_header(csv_path, header);
  std::string line;
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    line = fmt::format("{},{}", f, f / movie.rate_hz);
    for (float v : movie.frame(f)) fmt::format_to(std::back_inserter(line), ",{}", v);
    line += '\n';
    out << line;
  }
  csv::finish(out, csv_path);
}

}  // namespace tactile::movie
