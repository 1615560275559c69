#pragma once
// A live session's recording, written as it goes into a folder of its own:
//   latency.csv   frame,source_time_s,latency_ms,dropped (one row per camera frame)
//   tracks.csv    as `tactile capture --csv` writes it (the points of each strain frame)
//   edges.csv     as `tactile capture --csv` writes it
// appended in whole lines and flushed to the disk (fsync) at least once a second, so a session
// killed at any moment leaves files the project's CSV readers take, missing at most the last
// second; and at the end (the source's end, --seconds or Ctrl-C)
//   strain.h5     the strain movie of the session (tactile capture's schema)
//   movie.h5      the frames sent to the display, at its rate (each camera frame held)
// written atomically. The folder must be new or empty; its files are created new (never through
// a link planted there).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/live/live_session.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::live {

class SessionRecording {
 public:
  // Creates the folder and the three CSV files with their headers; throws std::runtime_error
  // naming the path and the OS's reason.
  explicit SessionRecording(const std::filesystem::path& dir);
  ~SessionRecording();
  SessionRecording(const SessionRecording&) = delete;
  SessionRecording& operator=(const SessionRecording&) = delete;

  // `callbacks` made to record into this too (each still calls what it called before).
  void attach(LiveCallbacks& callbacks);

  void frame(const FrameTiming& timing);
  void strain(const capture::StrainFrame& frame);
  void mapped(std::int64_t frame, const std::vector<float>& deflection_um);
  // Writes what is buffered and syncs it when a second has passed since the last time.
  void flush_if_due();
  // Flushes the CSV files and writes strain.h5 and movie.h5.
  void finish(const capture::Calibration& calibration, double camera_rate_hz,
              const movie::Layout& layout, double device_rate_hz, const std::string& provenance);

 private:
  struct Csv;
  std::filesystem::path dir_;
  std::vector<Csv> files_;  // latency, tracks, edges
  std::chrono::steady_clock::time_point last_flush_;
  std::vector<capture::StrainFrame> frames_;
  std::vector<std::pair<std::int64_t, std::vector<float>>> mapped_;
  std::int64_t last_frame_ = -1;
};

}  // namespace tactile::live
