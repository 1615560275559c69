#include "tactile/capture/strain_movie_io.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <type_traits>
#include <unordered_set>

#include <fmt/format.h>

#include "tactile/capture/calibration_io.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/value_checks.hpp"

namespace tactile::capture {

namespace {

using Dims = std::vector<hsize_t>;

hsize_t h(std::size_t n) {
  return static_cast<hsize_t>(n);
}

// The columns of /tracks, or of /frames' points (their "from" ends).
struct PointColumns {
  std::vector<std::int32_t> ids, frames, types;
  std::vector<double> px, mm;

  void add(const TrackedPoint& p) {
    ids.push_back(p.track_id);
    frames.push_back(p.frame);
    types.push_back(static_cast<std::int32_t>(p.type));
    px.insert(px.end(), {p.x_px, p.y_px});
    mm.insert(mm.end(), {p.x_mm, p.y_mm});
  }
};

// The /frames columns of a run of strain frames. The offsets are the ends of each frame's rows,
// counted over every frame added so far (a file's offsets start with a 0 before them).
struct FrameColumns {
  std::vector<std::int32_t> from, to, point_end, edge_end, triangle_end;
  std::vector<double> t_s;
  PointColumns points;
  std::vector<double> to_px, to_mm;
  std::vector<std::int32_t> edge_tracks, triangle_points;
  std::vector<double> edge_lengths, edge_rel;
  std::int32_t points_total = 0, edges_total = 0, triangles_total = 0;

  void add(const StrainFrame& f) {
    if (f.points_from.size() != f.points_to.size()) {
      throw std::invalid_argument(
          fmt::format("strain frame {}->{}: {} points_from but {} points_to", f.frame_from,
                      f.frame_to, f.points_from.size(), f.points_to.size()));
    }
    from.push_back(f.frame_from);
    to.push_back(f.frame_to);
    t_s.push_back(f.t_s);
    for (const auto& p : f.points_from) points.add(p);
    for (const auto& p : f.points_to) {
      to_px.insert(to_px.end(), {p.x_px, p.y_px});
      to_mm.insert(to_mm.end(), {p.x_mm, p.y_mm});
    }
    for (const auto& e : f.edges) {
      edge_tracks.insert(edge_tracks.end(), {e.track_a, e.track_b});
      edge_lengths.insert(edge_lengths.end(), {e.length_from_mm, e.length_to_mm});
      edge_rel.push_back(e.rel_change);
    }
    for (const auto& t : f.triangles) {
      triangle_points.insert(triangle_points.end(), t.point_index.begin(), t.point_index.end());
    }
    points_total += static_cast<std::int32_t>(f.points_from.size());
    edges_total += static_cast<std::int32_t>(f.edges.size());
    triangles_total += static_cast<std::int32_t>(f.triangles.size());
    point_end.push_back(points_total);
    edge_end.push_back(edges_total);
    triangle_end.push_back(triangles_total);
  }
  // Empties the columns; the running totals stay.
  void clear() {
    FrameColumns empty;
    empty.points_total = points_total;
    empty.edges_total = edges_total;
    empty.triangles_total = triangles_total;
    *this = std::move(empty);
  }
};

// The schema's datasets, each handed to `put(path, values, tail)` with its path from the root
// and the shape of one row (empty for a vector): the one list of them that both writers use.
template <typename Put>
void put_track_columns(const PointColumns& c, Put&& put) {
  put("tracks/track_id", c.ids, Dims{});
  put("tracks/type", c.types, Dims{});
  put("tracks/frame", c.frames, Dims{});
  put("tracks/position_px", c.px, Dims{2});
  put("tracks/position_mm", c.mm, Dims{2});
}

template <typename Put, typename PutOffsets>
void put_frame_columns(const FrameColumns& c, Put&& put, PutOffsets&& put_offsets) {
  put("frames/frame_from", c.from, Dims{});
  put("frames/frame_to", c.to, Dims{});
  put("frames/t_s", c.t_s, Dims{});
  put_offsets("frames/point_offset", c.point_end);
  put_offsets("frames/edge_offset", c.edge_end);
  put_offsets("frames/triangle_offset", c.triangle_end);
  put("frames/point_track_id", c.points.ids, Dims{});
  put("frames/point_type", c.points.types, Dims{});
  put("frames/point_position_px", c.points.px, Dims{2});
  put("frames/point_position_mm", c.points.mm, Dims{2});
  put("frames/point_to_position_px", c.to_px, Dims{2});
  put("frames/point_to_position_mm", c.to_mm, Dims{2});
  put("frames/edge_tracks", c.edge_tracks, Dims{2});
  put("frames/edge_length_mm", c.edge_lengths, Dims{2});
  put("frames/edge_rel_change", c.edge_rel, Dims{});
  put("frames/triangle_points", c.triangle_points, Dims{3});
}

// Everything but the tracks and the frames: the root's attributes and the calibration.
void write_header(H5::H5File& file, const StrainMovie& movie) {
  H5::Group root = file.openGroup("/");
  h5::write_attr(root, "format", kStrainMovieFormat);
  h5::write_attr(root, "format_version", std::int64_t{kStrainMovieFormatVersion});
  h5::write_attr(root, "frame_rate_hz", movie.frame_rate_hz);
  h5::write_attr(root, "span_frames", std::int64_t{movie.span_frames});
  h5::write_attr(root, "camera_frame_count", std::int64_t{movie.camera_frame_count});
  h5::write_attr(root, "field_width_mm", movie.field_width_mm);
  h5::write_attr(root, "field_height_mm", movie.field_height_mm);
  h5::write_attr(root, "units", "position: mm (and px); time: s; rel_change: dimensionless");
  h5::write_attr(root, "feature_types", "0=pore,1=ending,2=bifurcation");
  h5::write_provenance(root, movie.provenance);

  H5::Group cal = file.createGroup("/calibration");
  const Calibration& c = movie.calibration;
  h5::write_dataset(cal, "px_to_mm", std::vector<double>(c.px_to_mm.begin(), c.px_to_mm.end()),
                    {3, 3});
  h5::write_attr(cal, "mm_per_px", c.mm_per_px);
  h5::write_attr(cal, "image_width_px", std::int64_t{c.image_width_px});
  h5::write_attr(cal, "image_height_px", std::int64_t{c.image_height_px});
  h5::write_attr(cal, "method", c.method);
}

// /contact: every camera frame's cells, as frames x rows x columns. A map that does not fit the
// movie would make a file its reader refuses: refused here instead.
void write_contact(H5::H5File& file, const ContactMap& c, const StrainMovie& movie) {
  const Calibration& cal = movie.calibration;
  const ContactGrid fits =
      contact_grid_of_cells(cal.image_width_px, cal.image_height_px, c.grid.cell_px);
  if (c.grid.columns != fits.columns || c.grid.rows != fits.rows ||
      c.ridge_contrast.size() != c.in_contact.size() ||
      c.in_contact.size() != static_cast<std::size_t>(c.grid.cells()) *
                                 static_cast<std::size_t>(std::max(0, movie.camera_frame_count))) {
    throw std::invalid_argument(fmt::format(
        "write_strain_movie: a contact map of {} x {} cells of {} px, {} values, does not fit "
        "{} camera frames of {} x {} px",
        c.grid.columns, c.grid.rows, c.grid.cell_px, c.in_contact.size(), movie.camera_frame_count,
        cal.image_width_px, cal.image_height_px));
  }
  const auto frames = static_cast<std::size_t>(c.frame_count());
  if (c.per_frame() && (c.frame_threshold.size() != frames || c.frame_seen.size() != frames)) {
    throw std::invalid_argument(fmt::format(
        "write_strain_movie: a contact map of {} frames has {} frame thresholds and {} seen flags",
        frames, c.frame_threshold.size(), c.frame_seen.size()));
  }
  H5::Group g = file.createGroup("/contact");
  h5::write_attr(g, "cell_px", std::int64_t{c.grid.cell_px});
  const Dims dims{h(frames), h(static_cast<std::size_t>(c.grid.rows)),
                  h(static_cast<std::size_t>(c.grid.columns))};
  h5::write_dataset(g, "ridge_contrast", c.ridge_contrast, dims);
  h5::write_dataset(g, "in_contact",
                    std::vector<std::int32_t>(c.in_contact.begin(), c.in_contact.end()), dims);
  if (c.per_frame()) {
    h5::write_dataset(g, "frame_threshold", c.frame_threshold, Dims{h(frames)});
    h5::write_dataset(g, "seen",
                      std::vector<std::int32_t>(c.frame_seen.begin(), c.frame_seen.end()),
                      Dims{h(frames)});
  } else {
    h5::write_attr(g, "threshold", c.threshold);
  }
}

}  // namespace

void write_strain_movie(const std::filesystem::path& path, const StrainMovie& movie) {
  h5::write_file_atomically(path, [&](H5::H5File& file) {
    write_header(file, movie);
    H5::Group root = file.openGroup("/");
    const auto put = [&](const std::string& name, const auto& values, Dims tail) {
      std::size_t row = 1;
      for (hsize_t d : tail) row *= d;
      tail.insert(tail.begin(), h(values.size() / row));
      h5::write_dataset(root, name, values, tail);
    };
    PointColumns tracks;
    for (const auto& p : movie.tracks) tracks.add(p);
    file.createGroup("/tracks");
    put_track_columns(tracks, put);
    FrameColumns frames;
    for (const auto& f : movie.frames) frames.add(f);
    file.createGroup("/frames");
    const auto put_offsets = [&](const std::string& name, std::vector<std::int32_t> ends) {
      ends.insert(ends.begin(), 0);
      put(name, ends, Dims{});
    };
    put_frame_columns(frames, put, put_offsets);
    if (movie.contact.measured()) write_contact(file, movie.contact, movie);
  });
}

struct StrainMovieAppender::Columns {
  PointColumns tracks;
  FrameColumns frames;
  // Contact rows in camera frame order from the next one the file lacks.
  std::vector<double> contrast, threshold;
  std::vector<std::int32_t> in_contact, seen;
};

StrainMovieAppender::StrainMovieAppender(const std::filesystem::path& path,
                                         const StrainMovie& header)
    : file_(path), pending_(std::make_unique<Columns>()) {
  StrainMovie empty = header;
  empty.tracks.clear();
  empty.frames.clear();
  empty.camera_frame_count = 0;
  span_frames_ = header.span_frames;
  try {
    write_header(file_.file(), empty);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), e.getDetailMsg()));
  }
  const auto make = [&](const std::string& name, const auto& values, const Dims& tail) {
    file_.create_rows(name, tail, std::decay_t<decltype(values)>{});
  };
  // Offsets begin with the 0 before the first frame.
  const auto make_offsets = [&](const std::string& name, const std::vector<std::int32_t>&) {
    file_.create_rows(name, Dims{}, std::vector<std::int32_t>{0});
  };
  try {
    file_.file().createGroup("/tracks");
    put_track_columns(pending_->tracks, make);
    file_.file().createGroup("/frames");
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), e.getDetailMsg()));
  }
  put_frame_columns(pending_->frames, make, make_offsets);
  contact_grid_ = header.contact.grid;
  if (header.contact.measured()) {
    const Calibration& cal = header.calibration;
    const ContactGrid fits =
        contact_grid_of_cells(cal.image_width_px, cal.image_height_px, contact_grid_.cell_px);
    if (fits.columns != contact_grid_.columns || fits.rows != contact_grid_.rows) {
      throw std::invalid_argument(fmt::format(
          "StrainMovieAppender: a contact grid of {} x {} cells of {} px does not fit {} x {} px",
          contact_grid_.columns, contact_grid_.rows, contact_grid_.cell_px, cal.image_width_px,
          cal.image_height_px));
    }
    try {
      H5::Group g = file_.file().createGroup("/contact");
      h5::write_attr(g, "cell_px", std::int64_t{contact_grid_.cell_px});
    } catch (const H5::Exception& e) {
      throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), e.getDetailMsg()));
    }
    const Dims cells{h(static_cast<std::size_t>(contact_grid_.rows)),
                     h(static_cast<std::size_t>(contact_grid_.columns))};
    file_.create_rows("/contact/ridge_contrast", cells, std::vector<double>{});
    file_.create_rows("/contact/in_contact", cells, std::vector<std::int32_t>{});
    file_.create_rows("/contact/frame_threshold", Dims{}, std::vector<double>{});
    file_.create_rows("/contact/seen", Dims{}, std::vector<std::int32_t>{});
  }
  file_.start();
}

StrainMovieAppender::~StrainMovieAppender() = default;

std::vector<TrackedPoint> StrainMovieAppender::append(const StrainFrame& frame) {
  // A point becomes a row of /tracks when first seen: in any "to" end, or in a "from" end that
  // the previous strain frame's "to" end did not hold (a track detected at that frame, or the
  // first strain frame).
  std::vector<TrackedPoint> added;
  for (const auto& p : frame.points_from) {
    if (p.frame != last_frame_ || !last_to_tracks_.count(p.track_id)) added.push_back(p);
  }
  last_to_tracks_.clear();
  for (const auto& p : frame.points_to) {
    added.push_back(p);
    last_to_tracks_.insert(p.track_id);
  }
  last_frame_ = frame.frame_to;
  for (const auto& p : added) pending_->tracks.add(p);
  camera_frame_count_ = std::max<std::int64_t>(camera_frame_count_, frame.frame_to + 1);
  // The schema holds strain frames of one span; one measured across a missing frame is left out.
  if (frame.frame_to - frame.frame_from == span_frames_) {
    pending_->frames.add(frame);
  } else {
    ++frames_left_out_;
  }
  return added;
}

void StrainMovieAppender::append_contact(std::int64_t frame, double threshold_grey,
                                         std::vector<double> ridge_contrast,
                                         std::vector<std::uint8_t> in_contact) {
  if (!contact_grid_.cell_px || frame < contact_frames_) return;
  const auto cells = static_cast<std::size_t>(contact_grid_.cells());
  if (ridge_contrast.size() != cells || in_contact.size() != cells) {
    throw std::invalid_argument(
        fmt::format("StrainMovieAppender: camera frame {}'s contact has {} contrasts and {} cells "
                    "for a grid of {}",
                    frame, ridge_contrast.size(), in_contact.size(), cells));
  }
  held_contact_[frame] = {threshold_grey, true, std::move(ridge_contrast), std::move(in_contact)};
  take_held_contact();
}

void StrainMovieAppender::append_unseen(std::int64_t frame) {
  if (!contact_grid_.cell_px || frame < contact_frames_) return;
  held_contact_.try_emplace(frame);
  take_held_contact();
}

// Held rows move into the columns while they follow the file's last row without a frame missing.
void StrainMovieAppender::take_held_contact() {
  const auto cells = static_cast<std::size_t>(contact_grid_.cells());
  for (auto it = held_contact_.begin(); it != held_contact_.end() && it->first == contact_frames_;
       it = held_contact_.erase(it)) {
    ContactRow& row = it->second;
    if (!row.seen) {
      row.ridge_contrast.assign(cells, 0.0);
      row.in_contact.assign(cells, 0);
    }
    Columns& c = *pending_;
    c.contrast.insert(c.contrast.end(), row.ridge_contrast.begin(), row.ridge_contrast.end());
    c.in_contact.insert(c.in_contact.end(), row.in_contact.begin(), row.in_contact.end());
    c.threshold.push_back(row.threshold_grey);
    c.seen.push_back(row.seen ? 1 : 0);
    ++contact_frames_;
  }
}

void StrainMovieAppender::flush() {
  const auto append = [&](const std::string& name, const auto& values, const Dims&) {
    file_.append(name, values);
  };
  const auto append_offsets = [&](const std::string& name, const std::vector<std::int32_t>& ends) {
    file_.append(name, ends);
  };
  put_track_columns(pending_->tracks, append);
  put_frame_columns(pending_->frames, append, append_offsets);
  pending_->tracks = {};
  pending_->frames.clear();
  if (contact_grid_.cell_px) {
    file_.append("/contact/ridge_contrast", pending_->contrast);
    file_.append("/contact/in_contact", pending_->in_contact);
    file_.append("/contact/frame_threshold", pending_->threshold);
    file_.append("/contact/seen", pending_->seen);
    pending_->contrast.clear();
    pending_->in_contact.clear();
    pending_->threshold.clear();
    pending_->seen.clear();
    camera_frame_count_ = std::max(camera_frame_count_, contact_frames_);
  }
  file_.set_attr("/", "camera_frame_count", camera_frame_count_);
  file_.flush();
}

void StrainMovieAppender::close() {
  if (contact_grid_.cell_px) {
    // Frames never reported (the session ended between them) count as unseen: the map then
    // covers every camera frame of the movie.
    std::int64_t end = camera_frame_count_;
    if (!held_contact_.empty()) end = std::max(end, held_contact_.rbegin()->first + 1);
    for (std::int64_t f = contact_frames_; f < end; ++f) held_contact_.try_emplace(f);
    take_held_contact();
  }
  flush();
  file_.close();
}

namespace {

class Reader {
 public:
  explicit Reader(const std::filesystem::path& path) : name_(path.string()) {}

  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw FormatError(fmt::format("{}:{}: {}", name_, object, what));
  }
  std::string where(const std::string& object) const { return name_ + ":" + object; }

  // Reads a dataset of `rows` x `cols` (cols = 0 for a vector); rows = -1 accepts any.
  template <typename T>
  std::vector<T> read(const H5::Group& g, const std::string& group_name, const std::string& name,
                      long long rows, hsize_t cols) {
    Dims dims;
    const std::size_t rank = cols == 0 ? 1 : 2;
    const std::string obj = group_name + "/" + name;
    std::vector<T> data;
    if constexpr (std::is_same_v<T, double>) {
      data = h5::read_doubles(g, name, rank, dims, where(obj));
    } else {
      data = h5::read_ints(g, name, rank, dims, where(obj));
    }
    if (rows >= 0 && dims[0] != static_cast<hsize_t>(rows)) {
      fail(obj, fmt::format("has {} rows, expected {}", dims[0], rows));
    }
    if (cols != 0 && dims[1] != cols)
      fail(obj, fmt::format("has {} columns, expected {}", dims[1], cols));
    return data;
  }

 private:
  std::string name_;
};

FeatureType type_from(std::int32_t v, const Reader& r, const std::string& obj, std::size_t i) {
  if (v < 0 || v > 2) r.fail(obj, fmt::format("entry {} is type {}, expected 0, 1 or 2", i, v));
  return static_cast<FeatureType>(v);
}

void check_offsets(const Reader& r, const std::string& name, const std::vector<std::int32_t>& off,
                   std::size_t frames, std::size_t total) {
  if (off.size() != frames + 1) {
    r.fail("/frames/" + name, fmt::format("has {} rows, expected {}", off.size(), frames + 1));
  }
  if (off.front() != 0) r.fail("/frames/" + name, "does not start at 0");
  for (std::size_t i = 1; i < off.size(); ++i) {
    if (off[i] < off[i - 1]) r.fail("/frames/" + name, fmt::format("decreases at entry {}", i));
  }
  if (static_cast<std::size_t>(off.back()) != total) {
    r.fail("/frames/" + name,
           fmt::format("ends at {} but the data it indexes has {} entries", off.back(), total));
  }
}

// The rows of a file whose writer was killed while it grew (StrainMovieAppender): each dataset
// was written whole up to some row, but the datasets of one flush may have reached the disk in
// any order. What is read is the longest run of strain frames whose rows are all there.
struct FrameRows {
  std::vector<std::int32_t>& from;
  std::vector<std::int32_t>& to;
  std::vector<double>& t_s;
  std::vector<std::int32_t>& point_offset;
  std::vector<std::int32_t>& edge_offset;
  std::vector<std::int32_t>& triangle_offset;
  std::vector<std::int32_t>& point_track_id;
  std::vector<std::int32_t>& point_type;
  std::vector<double>& point_from_px;
  std::vector<double>& point_from_mm;
  std::vector<double>& point_to_px;
  std::vector<double>& point_to_mm;
  std::vector<double>& edge_rel;
  std::vector<std::int32_t>& edge_tracks;
  std::vector<double>& edge_lengths;
  std::vector<std::int32_t>& triangles;
};

void keep_whole_frames(FrameRows c, const std::unordered_set<std::int32_t>& known_tracks) {
  const auto offsets = [](const std::vector<std::int32_t>& off) {
    return off.empty() ? std::size_t{0} : off.size() - 1;
  };
  std::size_t frames = std::min({c.from.size(), c.to.size(), c.t_s.size(), offsets(c.point_offset),
                                 offsets(c.edge_offset), offsets(c.triangle_offset)});
  const std::size_t points =
      std::min({c.point_track_id.size(), c.point_type.size(), c.point_from_px.size() / 2,
                c.point_from_mm.size() / 2, c.point_to_px.size() / 2, c.point_to_mm.size() / 2});
  const std::size_t edges =
      std::min({c.edge_rel.size(), c.edge_tracks.size() / 2, c.edge_lengths.size() / 2});
  const std::size_t triangles = c.triangles.size() / 3;
  // A frame is kept when its rows are there and its points name tracks that are.
  const auto fits = [](const std::vector<std::int32_t>& off, std::size_t f, std::size_t rows) {
    return off[f] >= 0 && off[f] <= off[f + 1] && static_cast<std::size_t>(off[f + 1]) <= rows;
  };
  std::size_t kept = 0;
  while (kept < frames && fits(c.point_offset, kept, points) && fits(c.edge_offset, kept, edges) &&
         fits(c.triangle_offset, kept, triangles)) {
    bool tracks_there = true;
    for (auto i = c.point_offset[kept]; i < c.point_offset[kept + 1]; ++i) {
      tracks_there = tracks_there && known_tracks.count(c.point_track_id[i]) > 0;
    }
    if (!tracks_there) break;
    ++kept;
  }
  frames = kept;
  const auto cut = [](auto& v, std::size_t n) { v.resize(std::min(v.size(), n)); };
  cut(c.from, frames);
  cut(c.to, frames);
  cut(c.t_s, frames);
  for (auto* off : {&c.point_offset, &c.edge_offset, &c.triangle_offset}) cut(*off, frames + 1);
  const auto end = [&](const std::vector<std::int32_t>& off) {
    return off.empty() ? std::size_t{0} : static_cast<std::size_t>(off.back());
  };
  const std::size_t p = end(c.point_offset), e = end(c.edge_offset), t = end(c.triangle_offset);
  cut(c.point_track_id, p);
  cut(c.point_type, p);
  for (auto* xy : {&c.point_from_px, &c.point_from_mm, &c.point_to_px, &c.point_to_mm}) {
    cut(*xy, 2 * p);
  }
  cut(c.edge_rel, e);
  cut(c.edge_tracks, 2 * e);
  cut(c.edge_lengths, 2 * e);
  cut(c.triangles, 3 * t);
}

}  // namespace

namespace {

// Positions, lengths and times far beyond any fingertip image are damage, not measurements.
constexpr double kMaxAbsPositionPx = 1e6;
constexpr double kMaxAbsPositionMm = 1e4;
// Camera frames a strain movie may count: over four days at 240 Hz.
constexpr std::int64_t kMaxCameraFrames = 100000000;
// An edge's relative change of length: a length cannot fall below 0 (-1), and skin tears
// before it stretches to twice its length (+1); ten times that leaves room for a point tracked
// to the wrong ridge on a short edge, and still refuses values no skin can have.
constexpr double kMinRelChange = -1;
constexpr double kMaxRelChange = 10;

void check_positions(const std::vector<double>& xy, double max_abs, const Reader& r,
                     const std::string& obj) {
  checks::all_finite(xy, r.where(obj), "position");
  for (std::size_t i = 0; i < xy.size(); ++i) {
    if (std::abs(xy[i]) > max_abs) {
      r.fail(obj, fmt::format("entry {} is {}, beyond +-{}", i / 2, xy[i], max_abs));
    }
  }
}

// The field is the image seen through the calibration: a field that disagrees with it by more
// than a perspective could explain means one of the two is damaged (a movie with no tracks
// has no field to compare).
void check_field(const StrainMovie& m, const Reader& r) {
  if (m.tracks.empty()) return;
  const Calibration& c = m.calibration;
  const std::pair<const char*, double> sides[] = {
      {"field_width_mm", m.field_width_mm / (c.image_width_px * c.mm_per_px)},
      {"field_height_mm", m.field_height_mm / (c.image_height_px * c.mm_per_px)}};
  for (const auto& [name, ratio] : sides) {
    if (!(ratio > 0.5 && ratio < 2)) {
      r.fail("/", fmt::format("{} {} does not match the calibrated image ({} x {} px at {} mm "
                              "per px)",
                              name, name == sides[0].first ? m.field_width_mm : m.field_height_mm,
                              c.image_width_px, c.image_height_px, c.mm_per_px));
    }
  }
}

// A ridge contrast is the RMS of grey levels minus their local mean: it cannot exceed the
// 8-bit range.
constexpr double kMaxRidgeContrast = 255;
// Cells an unfinished file's contact map may lack and be read as unseen (a recording flushes
// every half second: a few hundred frames at most in a sound file).
constexpr hsize_t kMaxUnseenContactValues = hsize_t{1} << 24;

// /contact, checked against the movie's camera frames and calibrated image. A map of frame
// thresholds in an unfinished file (a live recording cut off) may be shorter or longer than the
// camera frames its counts say: the frames every dataset holds are taken (the camera frames are
// at least those), and frames beyond them are unseen.
ContactMap read_contact(const H5::Group& root, StrainMovie& m, const Reader& r, bool unfinished) {
  const std::string where = r.where("/contact");
  H5::Group g = h5::open_group(root, "contact", where);
  ContactMap c;
  const Calibration& cal = m.calibration;
  c.grid = contact_grid_of_cells(
      cal.image_width_px, cal.image_height_px,
      static_cast<std::int32_t>(checks::int_in_range(h5::read_attr_int(g, "cell_px", where), 1,
                                                     kMaxImageSidePx, where, "cell_px")));
  const bool per_frame = h5::has_child(g, "frame_threshold");
  if (per_frame == h5::has_attr(g, "threshold")) {
    r.fail("/contact", per_frame ? "has both a `threshold` attribute and a `frame_threshold` "
                                   "dataset: one or the other"
                                 : "has no threshold: a `threshold` attribute or a "
                                   "`frame_threshold` dataset is needed");
  }
  if (!per_frame) {
    c.threshold = checks::in_range(h5::read_attr_double(g, "threshold", where), 0,
                                   kMaxRidgeContrast, where, "threshold");
  }
  Dims contrast_dims, in_contact_dims, threshold_dims{0}, seen_dims{0};
  c.ridge_contrast =
      h5::read_doubles(g, "ridge_contrast", 3, contrast_dims, r.where("/contact/ridge_contrast"));
  std::vector<std::int32_t> in_contact =
      h5::read_ints(g, "in_contact", 3, in_contact_dims, r.where("/contact/in_contact"));
  std::vector<std::int32_t> seen;
  if (per_frame) {
    c.frame_threshold = h5::read_doubles(g, "frame_threshold", 1, threshold_dims,
                                         r.where("/contact/frame_threshold"));
    seen = h5::read_ints(g, "seen", 1, seen_dims, r.where("/contact/seen"));
  }
  const auto rows = static_cast<hsize_t>(c.grid.rows),
             columns = static_cast<hsize_t>(c.grid.columns);
  const auto cells = static_cast<std::size_t>(c.grid.cells());
  auto frames = static_cast<hsize_t>(m.camera_frame_count);
  const auto check_shape = [&](const std::string& name, const Dims& dims) {
    if (dims.size() != 3 || dims[0] != frames || dims[1] != rows || dims[2] != columns) {
      r.fail("/contact/" + name,
             fmt::format("has shape {} x {} x {}, expected {} x {} x {} (camera frames x rows x "
                         "columns of {} px cells over the {} x {} px image)",
                         dims.at(0), dims.at(1), dims.at(2), frames, rows, columns, c.grid.cell_px,
                         cal.image_width_px, cal.image_height_px));
    }
  };
  if (unfinished && per_frame) {
    // Cells of another grid are refused as they are; whole frames of this one are cut below.
    for (const auto& [name, dims] :
         {std::pair{"ridge_contrast", contrast_dims}, std::pair{"in_contact", in_contact_dims}}) {
      if (dims.at(1) != rows || dims.at(2) != columns) check_shape(name, dims);
    }
    const hsize_t whole =
        std::min({contrast_dims.at(0), in_contact_dims.at(0), threshold_dims.at(0), seen_dims.at(0),
                  static_cast<hsize_t>(kMaxCameraFrames)});
    if (whole > frames) frames = whole;
    m.camera_frame_count = static_cast<std::int32_t>(frames);
    contrast_dims[0] = in_contact_dims[0] = frames;
    // Unseen frames are added as zeros: no more than a damaged count could ask for in memory.
    if ((frames - whole) * cells > kMaxUnseenContactValues) {
      r.fail("/contact", fmt::format("holds {} camera frames, far fewer than the movie's {}: "
                                     "not the contact map of an unfinished recording",
                                     whole, frames));
    }
    // The whole frames (frames >= whole), then the unseen ones after them as zeros.
    c.ridge_contrast.resize(whole * cells);
    c.ridge_contrast.resize(frames * cells, 0.0);
    in_contact.resize(whole * cells);
    in_contact.resize(frames * cells, 0);
    c.frame_threshold.resize(whole);
    c.frame_threshold.resize(frames, 0.0);
    seen.resize(whole);
    seen.resize(frames, 0);
    threshold_dims = seen_dims = Dims{frames};
  }
  check_shape("ridge_contrast", contrast_dims);
  check_shape("in_contact", in_contact_dims);
  if (per_frame) {
    for (const auto& [name, dims] :
         {std::pair{"frame_threshold", threshold_dims}, std::pair{"seen", seen_dims}}) {
      if (dims.at(0) != frames) {
        r.fail(
            std::string("/contact/") + name,
            fmt::format("has {} values, expected one per camera frame ({})", dims.at(0), frames));
      }
    }
    c.frame_seen.reserve(seen.size());
    for (std::size_t f = 0; f < seen.size(); ++f) {
      if (seen[f] != 0 && seen[f] != 1) {
        r.fail("/contact/seen", fmt::format("camera frame {}: {} is neither 0 (dropped unseen) "
                                            "nor 1 (seen)",
                                            f, seen[f]));
      }
      if (!(c.frame_threshold[f] >= 0 && c.frame_threshold[f] <= kMaxRidgeContrast)) {
        r.fail("/contact/frame_threshold",
               fmt::format("camera frame {}: threshold {} is out of range: must be from 0 to {} "
                           "grey levels",
                           f, c.frame_threshold[f], kMaxRidgeContrast));
      }
      c.frame_seen.push_back(static_cast<std::uint8_t>(seen[f]));
    }
  }
  const auto cell_name = [&](std::size_t i) {
    return fmt::format("camera frame {}, cell row {}, column {}", i / cells,
                       i % cells / static_cast<std::size_t>(c.grid.columns),
                       i % static_cast<std::size_t>(c.grid.columns));
  };
  c.in_contact.reserve(in_contact.size());
  for (std::size_t i = 0; i < in_contact.size(); ++i) {
    const double contrast = c.ridge_contrast[i];
    if (!(contrast >= 0 && contrast <= kMaxRidgeContrast)) {
      r.fail("/contact/ridge_contrast",
             fmt::format("{}: ridge contrast {} is out of range: must be from 0 to {} grey levels",
                         cell_name(i), contrast, kMaxRidgeContrast));
    }
    if (in_contact[i] != 0 && in_contact[i] != 1) {
      r.fail("/contact/in_contact", fmt::format("{}: {} is neither 0 (no contact) nor 1 (contact)",
                                                cell_name(i), in_contact[i]));
    }
    const std::size_t frame = i / cells;
    if (per_frame && seen[frame] == 0) {
      if (contrast != 0 || in_contact[i] != 0) {
        r.fail("/contact/in_contact",
               fmt::format("{}: the frame is marked unseen, but the cell has contrast {} and is "
                           "marked {} (an unseen frame's cells are 0, out of contact)",
                           cell_name(i), contrast, in_contact[i] == 1 ? "in contact" : "out"));
      }
    } else {
      const double threshold = per_frame ? c.frame_threshold[frame] : c.threshold;
      if ((in_contact[i] == 1) != (contrast >= threshold)) {
        r.fail("/contact/in_contact",
               fmt::format("{}: marked {} but its ridge contrast {} is {} the threshold {}",
                           cell_name(i), in_contact[i] == 1 ? "in contact" : "out of contact",
                           contrast, contrast >= threshold ? "at or above" : "below", threshold));
      }
    }
    c.in_contact.push_back(static_cast<std::uint8_t>(in_contact[i]));
  }
  return c;
}

StrainMovie read_strain_movie_checked(const std::filesystem::path& path);

}  // namespace

StrainMovie read_strain_movie(const std::filesystem::path& path, h5::ReadingProcess* process) {
  return h5::read_guarded<&read_strain_movie_checked>(path, "a strain movie", process);
}

namespace {

StrainMovie read_strain_movie_checked(const std::filesystem::path& path) {
  Reader r(path);
  bool unfinished = false;
  H5::H5File file = h5::open_for_reading(path, &unfinished);
  // An unfinished file's datasets may be longer than what its counts say: read every row.
  const auto need = [&](long long rows) { return unfinished ? -1 : rows; };
  H5::Group root = h5::open_group(file, "/", r.where("/"));
  const std::string format = h5::read_attr_string(root, "format", r.where("/"));
  if (format != kStrainMovieFormat) {
    r.fail("/", fmt::format("format is '{}', expected '{}'", format, kStrainMovieFormat));
  }
  const auto version = h5::read_attr_int(root, "format_version", r.where("/"));
  if (version != kStrainMovieFormatVersion) {
    r.fail("/", fmt::format("format_version {} is not supported (this program reads {})", version,
                            kStrainMovieFormatVersion));
  }
  StrainMovie m;
  // The same camera rates `capture --rate-hz` takes.
  m.frame_rate_hz = checks::in_range(h5::read_attr_double(root, "frame_rate_hz", r.where("/")), 1,
                                     100000, r.where("/"), "frame_rate_hz");
  m.span_frames = static_cast<std::int32_t>(
      checks::int_in_range(h5::read_attr_int(root, "span_frames", r.where("/")), 1, 1000000,
                           r.where("/"), "span_frames"));
  m.camera_frame_count = static_cast<std::int32_t>(
      checks::int_in_range(h5::read_attr_int(root, "camera_frame_count", r.where("/")), 0,
                           kMaxCameraFrames, r.where("/"), "camera_frame_count"));
  m.field_width_mm = checks::in_range(h5::read_attr_double(root, "field_width_mm", r.where("/")), 0,
                                      kMaxAbsPositionMm, r.where("/"), "field_width_mm");
  m.field_height_mm = checks::in_range(h5::read_attr_double(root, "field_height_mm", r.where("/")),
                                       0, kMaxAbsPositionMm, r.where("/"), "field_height_mm");
  m.provenance = h5::read_provenance(root, r.where("/"));
  // Files written before the provenance attributes held what the frames came from as `source`
  // and the writer's version and time unprefixed.
  if (!h5::has_attr(root, "provenance_input")) {
    const auto old = [&](const char* name, std::string& field) {
      if (field.empty() && h5::has_attr(root, name))
        field = h5::read_attr_string(root, name, r.where("/"));
    };
    old("source", m.provenance.input);
    old("program_version", m.provenance.program_version);
    old("created_utc", m.provenance.created_utc);
  }

  H5::Group cal = h5::open_group(root, "calibration", r.where("/calibration"));
  const auto hm = r.read<double>(cal, "/calibration", "px_to_mm", 3, 3);
  std::copy(hm.begin(), hm.end(), m.calibration.px_to_mm.begin());
  m.calibration.mm_per_px = h5::read_attr_double(cal, "mm_per_px", r.where("/calibration"));
  m.calibration.image_width_px =
      static_cast<int>(h5::read_attr_int(cal, "image_width_px", r.where("/calibration")));
  m.calibration.image_height_px =
      static_cast<int>(h5::read_attr_int(cal, "image_height_px", r.where("/calibration")));
  m.calibration.method = h5::read_attr_string(cal, "method", r.where("/calibration"));
  // Cast above from 64 bits: range-checked on the values as read, before any narrowing hides it.
  checks::int_in_range(h5::read_attr_int(cal, "image_width_px", r.where("/calibration")), 1,
                       kMaxImageSidePx, r.where("/calibration"), "image_width_px");
  checks::int_in_range(h5::read_attr_int(cal, "image_height_px", r.where("/calibration")), 1,
                       kMaxImageSidePx, r.where("/calibration"), "image_height_px");
  check_calibration(m.calibration, r.where("/calibration"));

  H5::Group tg = h5::open_group(root, "tracks", r.where("/tracks"));
  auto ids = r.read<std::int32_t>(tg, "/tracks", "track_id", -1, 0);
  const auto n = static_cast<long long>(ids.size());
  auto tframes = r.read<std::int32_t>(tg, "/tracks", "frame", need(n), 0);
  auto ttypes = r.read<std::int32_t>(tg, "/tracks", "type", need(n), 0);
  auto tpx = r.read<double>(tg, "/tracks", "position_px", need(n), 2);
  auto tmm = r.read<double>(tg, "/tracks", "position_mm", need(n), 2);
  if (unfinished) {
    // The rows every column has; the camera frames are at least those of the points kept
    // (the count is written after them).
    const std::size_t k =
        std::min({ids.size(), tframes.size(), ttypes.size(), tpx.size() / 2, tmm.size() / 2});
    ids.resize(k);
    tframes.resize(k);
    ttypes.resize(k);
    tpx.resize(2 * k);
    tmm.resize(2 * k);
    for (const auto f : tframes) {
      if (f >= m.camera_frame_count && f < kMaxCameraFrames) m.camera_frame_count = f + 1;
    }
  }
  check_positions(tpx, kMaxAbsPositionPx, r, "/tracks/position_px");
  check_positions(tmm, kMaxAbsPositionMm, r, "/tracks/position_mm");
  std::unordered_set<std::int32_t> known_tracks;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (tframes[i] < 0 || tframes[i] >= m.camera_frame_count) {
      r.fail("/tracks/frame", fmt::format("entry {} is frame {}, outside 0..{}", i, tframes[i],
                                          m.camera_frame_count - 1));
    }
    m.tracks.push_back({ids[i], tframes[i], type_from(ttypes[i], r, "/tracks/type", i), tpx[2 * i],
                        tpx[2 * i + 1], tmm[2 * i], tmm[2 * i + 1]});
    known_tracks.insert(ids[i]);
  }

  check_field(m, r);

  H5::Group fg = h5::open_group(root, "frames", r.where("/frames"));
  auto from = r.read<std::int32_t>(fg, "/frames", "frame_from", -1, 0);
  const auto nf = static_cast<long long>(from.size());
  auto to = r.read<std::int32_t>(fg, "/frames", "frame_to", need(nf), 0);
  auto t_s = r.read<double>(fg, "/frames", "t_s", need(nf), 0);
  auto pid = r.read<std::int32_t>(fg, "/frames", "point_track_id", -1, 0);
  const auto np = static_cast<long long>(pid.size());
  auto ptype = r.read<std::int32_t>(fg, "/frames", "point_type", need(np), 0);
  auto pfpx = r.read<double>(fg, "/frames", "point_position_px", need(np), 2);
  auto pfmm = r.read<double>(fg, "/frames", "point_position_mm", need(np), 2);
  auto ptpx = r.read<double>(fg, "/frames", "point_to_position_px", need(np), 2);
  auto ptmm = r.read<double>(fg, "/frames", "point_to_position_mm", need(np), 2);
  auto erel = r.read<double>(fg, "/frames", "edge_rel_change", -1, 0);
  const auto ne = static_cast<long long>(erel.size());
  auto etracks = r.read<std::int32_t>(fg, "/frames", "edge_tracks", need(ne), 2);
  auto elen = r.read<double>(fg, "/frames", "edge_length_mm", need(ne), 2);
  auto tri = r.read<std::int32_t>(fg, "/frames", "triangle_points", -1, 3);
  auto poff = r.read<std::int32_t>(fg, "/frames", "point_offset", need(nf + 1), 0);
  auto eoff = r.read<std::int32_t>(fg, "/frames", "edge_offset", need(nf + 1), 0);
  auto toff = r.read<std::int32_t>(fg, "/frames", "triangle_offset", need(nf + 1), 0);
  if (unfinished) {
    keep_whole_frames({from, to, t_s, poff, eoff, toff, pid, ptype, pfpx, pfmm, ptpx, ptmm, erel,
                       etracks, elen, tri},
                      known_tracks);
    for (const auto f : to) {
      if (f >= m.camera_frame_count && f < kMaxCameraFrames) m.camera_frame_count = f + 1;
    }
  }
  check_positions(pfpx, kMaxAbsPositionPx, r, "/frames/point_position_px");
  check_positions(pfmm, kMaxAbsPositionMm, r, "/frames/point_position_mm");
  check_positions(ptpx, kMaxAbsPositionPx, r, "/frames/point_to_position_px");
  check_positions(ptmm, kMaxAbsPositionMm, r, "/frames/point_to_position_mm");
  check_positions(elen, kMaxAbsPositionMm, r, "/frames/edge_length_mm");
  for (std::size_t i = 0; i < elen.size(); ++i) {
    if (elen[i] < 0) r.fail("/frames/edge_length_mm", fmt::format("entry {} is negative", i / 2));
  }
  checks::all_finite(erel, r.where("/frames/edge_rel_change"), "edge_rel_change");
  checks::all_finite(t_s, r.where("/frames/t_s"), "t_s");
  check_offsets(r, "point_offset", poff, from.size(), pid.size());
  check_offsets(r, "edge_offset", eoff, from.size(), erel.size());
  check_offsets(r, "triangle_offset", toff, from.size(), tri.size() / 3);

  for (std::size_t f = 0; f < from.size(); ++f) {
    StrainFrame sf;
    sf.frame_from = from[f];
    sf.frame_to = to[f];
    sf.t_s = t_s[f];
    if (sf.frame_from < 0 || sf.frame_to < 0 || sf.frame_to >= m.camera_frame_count) {
      r.fail("/frames", fmt::format("strain frame {} goes from frame {} to {}, outside 0..{}", f,
                                    sf.frame_from, sf.frame_to, m.camera_frame_count - 1));
    }
    if (sf.frame_to - sf.frame_from != m.span_frames) {
      r.fail("/frames", fmt::format("strain frame {} goes from frame {} to {}, but span_frames is "
                                    "{}",
                                    f, sf.frame_from, sf.frame_to, m.span_frames));
    }
    std::set<std::int32_t> in_frame;
    for (auto i = static_cast<std::size_t>(poff[f]); i < static_cast<std::size_t>(poff[f + 1]);
         ++i) {
      if (!known_tracks.count(pid[i])) {
        r.fail("/frames/point_track_id",
               fmt::format("point {} of strain frame {} names track {}, which is not in /tracks", i,
                           f, pid[i]));
      }
      const FeatureType type = type_from(ptype[i], r, "/frames/point_type", i);
      sf.points_from.push_back({pid[i], sf.frame_from, type, pfpx[2 * i], pfpx[2 * i + 1],
                                pfmm[2 * i], pfmm[2 * i + 1]});
      sf.points_to.push_back(
          {pid[i], sf.frame_to, type, ptpx[2 * i], ptpx[2 * i + 1], ptmm[2 * i], ptmm[2 * i + 1]});
      in_frame.insert(pid[i]);
    }
    for (auto i = static_cast<std::size_t>(eoff[f]); i < static_cast<std::size_t>(eoff[f + 1]);
         ++i) {
      const std::int32_t a = etracks[2 * i];
      const std::int32_t b = etracks[2 * i + 1];
      for (std::int32_t t : {a, b}) {
        if (!known_tracks.count(t)) {
          r.fail("/frames/edge_tracks",
                 fmt::format("edge {} names track {}, which does not exist in /tracks", i, t));
        }
        if (!in_frame.count(t)) {
          r.fail("/frames/edge_tracks",
                 fmt::format("edge {} names track {}, which is not a point of strain frame {}", i,
                             t, f));
        }
      }
      if (!(erel[i] >= kMinRelChange && erel[i] <= kMaxRelChange)) {
        r.fail("/frames/edge_rel_change",
               fmt::format("strain frame {} (camera frames {} to {}): edge {} (tracks {} and {}) "
                           "changed its length by {}, out of range: must be from {} to {} (a "
                           "length cannot shrink below 0; skin tears long before it doubles)",
                           f, sf.frame_from, sf.frame_to, i, a, b, erel[i], kMinRelChange,
                           kMaxRelChange));
      }
      sf.edges.push_back({a, b, elen[2 * i], elen[2 * i + 1], erel[i]});
    }
    const auto npts = static_cast<std::int32_t>(sf.points_from.size());
    for (auto i = static_cast<std::size_t>(toff[f]); i < static_cast<std::size_t>(toff[f + 1]);
         ++i) {
      StrainTriangle t{{tri[3 * i], tri[3 * i + 1], tri[3 * i + 2]}};
      for (std::int32_t k : t.point_index) {
        if (k < 0 || k >= npts) {
          r.fail("/frames/triangle_points",
                 fmt::format("triangle {} uses point {}, but strain frame {} has {} points", i, k,
                             f, npts));
        }
      }
      sf.triangles.push_back(t);
    }
    m.frames.push_back(std::move(sf));
  }
  // Written by capture and live recordings; absent from files written before it was measured.
  // An unfinished file's map is taken only when it is one written as the frames came.
  if (h5::has_child(root, "contact") &&
      (!unfinished ||
       h5::has_child(h5::open_group(root, "contact", r.where("/contact")), "frame_threshold"))) {
    m.contact = read_contact(root, m, r, unfinished);
  }
  return m;
}

}  // namespace

std::string tracks_csv_row(const TrackedPoint& p) {
  return fmt::format("{},{},{},{:.4f},{:.4f},{:.6f},{:.6f}\n", p.track_id, p.frame,
                     feature_type_name(p.type), p.x_px, p.y_px, p.x_mm, p.y_mm);
}

std::string edges_csv_rows(const StrainFrame& f) {
  std::string rows;
  for (const auto& edge : f.edges) {
    rows +=
        fmt::format("{},{},{},{},{:.6f},{:.6f},{:.7f}\n", f.frame_from, f.frame_to, edge.track_a,
                    edge.track_b, edge.length_from_mm, edge.length_to_mm, edge.rel_change);
  }
  return rows;
}

void export_strain_csv(const std::filesystem::path& dir, const StrainMovie& movie) {
  std::filesystem::create_directories(dir);
  const auto tracks_path = dir / "tracks.csv";
  auto t = csv::open_with_header(tracks_path, std::string(kTracksCsvHeader));
  for (const auto& p : movie.tracks) t << tracks_csv_row(p);
  csv::finish(t, tracks_path);
  const auto edges_path = dir / "edges.csv";
  auto e = csv::open_with_header(edges_path, std::string(kEdgesCsvHeader));
  for (const auto& f : movie.frames) e << edges_csv_rows(f);
  csv::finish(e, edges_path);
}

}  // namespace tactile::capture
