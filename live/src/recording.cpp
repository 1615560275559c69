// A live session's recording; see recording.hpp.

#include "tactile/live/recording.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/version.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::live {

namespace fs = std::filesystem;

// One CSV file appended in whole lines: a buffer written with one write() and then synced.
struct SessionRecording::Csv {
  fs::path path;
  int fd = -1;
  std::string pending;

  void flush() {
    std::size_t done = 0;
    while (done < pending.size()) {
      const ssize_t n = ::write(fd, pending.data() + done, pending.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        throw std::runtime_error(
            fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
      }
      done += static_cast<std::size_t>(n);
    }
    pending.clear();
    ::fdatasync(fd);
  }
};

SessionRecording::SessionRecording(const fs::path& dir) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw std::runtime_error(fmt::format("cannot make {}: {}", dir.string(), ec.message()));
  }
  const std::pair<const char*, std::string> files[] = {
      {"latency.csv", "frame,source_time_s,latency_ms,dropped"},
      {"tracks.csv", std::string(capture::kTracksCsvHeader)},
      {"edges.csv", std::string(capture::kEdgesCsvHeader)}};
  for (const auto& [name, header] : files) {
    Csv csv;
    csv.path = dir / name;
    // New files only, and never through a link: the folder was checked empty, so anything there
    // now was planted.
    csv.fd = ::open(csv.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (csv.fd < 0) {
      const int error = errno;
      for (auto& f : files_) ::close(f.fd);
      throw std::runtime_error(
          fmt::format("cannot create {}: {}", csv.path.string(), std::strerror(error)));
    }
    csv.pending = header + "\n";
    files_.push_back(std::move(csv));
  }
  for (auto& f : files_) f.flush();
  last_flush_ = std::chrono::steady_clock::now();
}

SessionRecording::~SessionRecording() {
  for (auto& f : files_) {
    try {
      f.flush();
    } catch (const std::exception&) {
      // A destructor cannot report; finish() reports a failed write.
    }
    ::close(f.fd);
  }
}

void SessionRecording::attach(LiveCallbacks& callbacks) {
  callbacks.frame_done = [this, before = callbacks.frame_done](const FrameTiming& t) {
    before(t);
    frame(t);
  };
  callbacks.strain = [this, before = callbacks.strain](const capture::StrainFrame& f) {
    before(f);
    strain(f);
  };
  callbacks.mapped = [this, before = callbacks.mapped](std::int64_t frame,
                                                       const std::vector<float>& d) {
    before(frame, d);
    mapped(frame, d);
  };
}

void SessionRecording::frame(const FrameTiming& t) {
  files_[0].pending += fmt::format("{},{:.6f},{},{}\n", t.frame, t.source_time_s,
                                   t.dropped ? std::string() : fmt::format("{:.3f}", t.latency_ms),
                                   t.dropped ? 1 : 0);
  flush_if_due();
}

void SessionRecording::strain(const capture::StrainFrame& frame) {
  // A point's position in its first strain frame's "from" end, then each "to" end.
  for (const auto& p : frame.points_from) {
    if (p.frame > last_frame_) files_[1].pending += capture::tracks_csv_row(p);
  }
  for (const auto& p : frame.points_to) files_[1].pending += capture::tracks_csv_row(p);
  last_frame_ = frame.frame_to;
  files_[2].pending += capture::edges_csv_rows(frame);
  frames_.push_back(frame);
}

void SessionRecording::mapped(std::int64_t frame, const std::vector<float>& deflection_um) {
  mapped_.emplace_back(frame, deflection_um);
}

void SessionRecording::flush_if_due() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ < std::chrono::seconds(1)) return;
  for (auto& f : files_) f.flush();
  last_flush_ = now;
}

void SessionRecording::finish(const capture::Calibration& calibration, double camera_rate_hz,
                              const movie::Layout& layout, double device_rate_hz,
                              const std::string& provenance) {
  for (auto& f : files_) f.flush();
  capture::StrainMovie strain;
  strain.frame_rate_hz = camera_rate_hz;
  strain.span_frames = 1;
  strain.calibration = calibration;
  strain.field_width_mm = calibration.image_width_px * calibration.mm_per_px;
  strain.field_height_mm = calibration.image_height_px * calibration.mm_per_px;
  strain.provenance.method = "live";
  strain.provenance.input = provenance;
  strain.provenance.program_version = kVersion;
  // Every point of every track, ordered by track, then frame (the schema's order).
  std::map<std::pair<std::int32_t, std::int32_t>, capture::TrackedPoint> points;
  std::int32_t last = 0;
  for (const auto& f : frames_) {
    // The schema holds strain frames of one span; one measured across a dropped frame spans
    // two (it stays in edges.csv, whose rows say their frames).
    if (f.frame_to - f.frame_from != 1) continue;
    for (const auto& p : f.points_from) points[{p.track_id, p.frame}] = p;
    for (const auto& p : f.points_to) points[{p.track_id, p.frame}] = p;
    last = std::max(last, f.frame_to);
    strain.frames.push_back(f);
  }
  for (const auto& [key, p] : points) strain.tracks.push_back(p);
  strain.camera_frame_count = strain.frames.empty() ? 0 : last + 1;
  if (!strain.frames.empty()) capture::write_strain_movie(dir_ / "strain.h5", strain);

  movie::TactileMovie movie;
  movie.layout = layout;
  movie.rate_hz = device_rate_hz;
  const std::size_t n =
      static_cast<std::size_t>(layout.rows) * static_cast<std::size_t>(layout.cols);
  if (!mapped_.empty()) {
    // As played: each camera frame held from its time until the next camera frame's.
    const double t_end = (mapped_.back().first + 1) / camera_rate_hz;
    const auto frames = static_cast<std::int64_t>(std::floor(t_end * device_rate_hz));
    std::size_t k = 0;
    for (std::int64_t j = 0; j < frames; ++j) {
      const double t = j / device_rate_hz;
      while (k + 1 < mapped_.size() && mapped_[k + 1].first / camera_rate_hz <= t) ++k;
      const auto& d = mapped_[k].second;
      movie.deflection_um.insert(movie.deflection_um.end(), d.begin(), d.begin() + n);
    }
    movie.frame_count = static_cast<std::int32_t>(frames);
    movie.provenance.method = "live";
    movie.provenance.input = provenance;
    movie.provenance.program_version = kVersion;
    if (movie.frame_count > 0) movie::write_tactile_movie(dir_ / "movie.h5", movie);
  }
}

}  // namespace tactile::live
