// A live session's recording; see recording.hpp.

#include "tactile/live/recording.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <variant>

#include "frames_video.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/provenance.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::live {

namespace fs = std::filesystem;

namespace {

// Often enough that a kill loses at most a second, counting the time a batch waits.
constexpr auto kFlushPeriod = std::chrono::milliseconds(500);

// One CSV file appended in whole lines: a buffer written with one write() and then synced.
struct Csv {
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

struct Mapped {
  std::int64_t frame = 0;
  std::vector<float> deflection_um;
};

struct Received {
  std::int64_t frame = 0;
  double time_s = 0;
  capture::GrayImage image;
};

using Event =
    std::variant<SessionStart, FrameTiming, capture::StrainFrame, Mapped, Received, FrameContact>;

}  // namespace

struct SessionRecording::Writer {
  fs::path dir;
  std::vector<Csv> csv;  // latency, tracks, edges
  std::optional<capture::StrainMovieAppender> strain;
  std::optional<movie::TactileMovieAppender> movie;
  std::optional<FramesVideo> video;
  // Frames received before the session started (its first frame's work): written then.
  std::vector<Received> early;
  // Frames dropped before it started: unseen in strain.h5's contact map.
  std::vector<std::int64_t> early_unseen;
  bool started = false;
  SessionStart start;
  // The movie as played: the last mapped frame, held until the next one's time.
  std::optional<Mapped> held;
  std::int64_t device_frames = 0;
  // Strain frames handed over, and of them those strain.h5 left out (its frames are of one span:
  // one measured across a dropped frame is in edges.csv only). Set by the writer's thread, read
  // after it has been joined.
  std::int64_t strain_frames = 0;
  std::int64_t strain_frames_left_out = 0;

  std::mutex mutex;
  std::condition_variable wake;
  std::deque<Event> events;
  bool closing = false;
  std::exception_ptr failure;
  std::thread thread;

  void push(Event e) {
    {
      std::lock_guard lock(mutex);
      events.push_back(std::move(e));
    }
    wake.notify_one();
  }

  // Device frames j with j / device rate before `until_s`, each holding the last mapped frame.
  void play_until(double until_s) {
    if (!held || !movie) return;
    while (device_frames / start.device_rate_hz < until_s - 1e-12) {
      movie->append(held->deflection_um);
      ++device_frames;
    }
  }

  void handle(Event& e) {
    if (auto* s = std::get_if<SessionStart>(&e)) {
      start = *s;
      capture::StrainMovie header;
      header.frame_rate_hz = s->camera_rate_hz;
      header.span_frames = 1;
      header.calibration = s->calibration;
      header.field_width_mm = s->calibration.image_width_px * s->calibration.mm_per_px;
      header.field_height_mm = s->calibration.image_height_px * s->calibration.mm_per_px;
      header.provenance = make_provenance(s->source, "live");
      header.contact.grid = s->contact_grid;
      strain.emplace(dir / "strain.h5", header);
      for (const std::int64_t f : early_unseen) strain->append_unseen(f);
      early_unseen.clear();
      movie::TactileMovie movie_header;
      movie_header.layout = s->layout;
      movie_header.rate_hz = s->device_rate_hz;
      movie_header.provenance = header.provenance;
      movie.emplace(dir / "movie.h5", movie_header);
      started = true;
      for (auto& r : early) receive(r);
      early.clear();
    } else if (auto* r = std::get_if<Received>(&e)) {
      if (started) {
        receive(*r);
      } else {
        early.push_back(std::move(*r));
      }
    } else if (auto* t = std::get_if<FrameTiming>(&e)) {
      if (t->dropped && strain) strain->append_unseen(t->frame);
      if (t->dropped && !strain) early_unseen.push_back(t->frame);
      csv[0].pending += fmt::format(
          "{},{:.6f},{},{}\n", t->frame, t->source_time_s,
          t->dropped ? std::string() : fmt::format("{:.3f}", t->latency_ms), t->dropped ? 1 : 0);
    } else if (auto* f = std::get_if<capture::StrainFrame>(&e)) {
      if (!strain) return;
      for (const auto& p : strain->append(*f)) csv[1].pending += capture::tracks_csv_row(p);
      csv[2].pending += capture::edges_csv_rows(*f);
      ++strain_frames;
      strain_frames_left_out = strain->frames_left_out();
    } else if (auto* c = std::get_if<FrameContact>(&e)) {
      if (strain) {
        strain->append_contact(c->frame, c->threshold_grey, std::move(c->ridge_contrast),
                               std::move(c->in_contact));
      }
    } else if (auto* m = std::get_if<Mapped>(&e)) {
      if (!movie) return;
      // The first mapped frame also stands for the device frames before it.
      if (!held) held = *m;
      play_until(m->frame / start.camera_rate_hz);
      held = std::move(*m);
    }
  }

  void receive(const Received& r) {
    if (!video) {
      video.emplace(dir / "frames.mkv", r.image.width_px, r.image.height_px, start.camera_rate_hz);
    }
    video->write(r.image, r.time_s);
  }

  void flush_all() {
    for (auto& f : csv) f.flush();
    if (video) video->flush();
    if (strain) strain->flush();
    if (movie) movie->flush();
  }

  void run() {
    auto last_flush = std::chrono::steady_clock::now();
    for (;;) {
      std::deque<Event> batch;
      bool last = false;
      {
        std::unique_lock lock(mutex);
        wake.wait_for(lock, kFlushPeriod, [&] { return closing || !events.empty(); });
        batch.swap(events);
        last = closing;
      }
      if (!failure) {
        try {
          for (auto& e : batch) handle(e);
          const auto now = std::chrono::steady_clock::now();
          if (last || now - last_flush >= kFlushPeriod) {
            if (last && held) play_until((held->frame + 1) / start.camera_rate_hz);
            flush_all();
            last_flush = now;
          }
        } catch (...) {
          failure = std::current_exception();
        }
      }
      if (last) break;
    }
    try {
      if (strain) strain->close();
      if (movie) movie->close();
      if (video) video->close();
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
    for (auto& f : csv) ::close(f.fd);
  }
};

SessionRecording::SessionRecording(const fs::path& dir) : writer_(std::make_unique<Writer>()) {
  writer_->dir = dir;
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
      for (auto& f : writer_->csv) ::close(f.fd);
      throw std::runtime_error(
          fmt::format("cannot create {}: {}", csv.path.string(), std::strerror(error)));
    }
    csv.pending = header + "\n";
    writer_->csv.push_back(std::move(csv));
  }
  for (auto& f : writer_->csv) f.flush();
  writer_->thread = std::thread([w = writer_.get()] { w->run(); });
}

SessionRecording::~SessionRecording() {
  try {
    finish();
  } catch (const std::exception&) {
    // A destructor cannot report; finish() called before it does.
  }
}

void SessionRecording::attach(LiveCallbacks& callbacks) {
  Writer* w = writer_.get();
  callbacks.received = [w, before = callbacks.received](std::int64_t frame, double time_s,
                                                        const capture::GrayImage& image) {
    before(frame, time_s, image);
    w->push(Received{frame, time_s, image});
  };
  callbacks.started = [w, before = callbacks.started](const SessionStart& s) {
    before(s);
    w->push(s);
  };
  callbacks.frame_done = [w, before = callbacks.frame_done](const FrameTiming& t) {
    before(t);
    w->push(t);
  };
  callbacks.contact = [w, before = callbacks.contact](const FrameContact& c) {
    before(c);
    w->push(c);
  };
  callbacks.strain = [w, before = callbacks.strain](const capture::StrainFrame& f) {
    before(f);
    w->push(f);
  };
  callbacks.mapped = [w, before = callbacks.mapped](std::int64_t frame,
                                                    const std::vector<float>& d) {
    before(frame, d);
    w->push(Mapped{frame, d});
  };
}

void SessionRecording::finish() {
  if (!writer_->thread.joinable()) return;
  {
    std::lock_guard lock(writer_->mutex);
    writer_->closing = true;
  }
  writer_->wake.notify_one();
  writer_->thread.join();
  if (writer_->failure) std::rethrow_exception(writer_->failure);
}

RecordedStrain SessionRecording::strain_frames() const {
  if (writer_->thread.joinable()) {
    throw std::logic_error("SessionRecording::strain_frames: asked before finish()");
  }
  return {writer_->strain_frames, writer_->strain_frames_left_out};
}

}  // namespace tactile::live
