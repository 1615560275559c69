#pragma once
// A live session's recording, written as it goes into a folder of its own:
//   latency.csv   frame,source_time_s,latency_ms,dropped (one row per camera frame)
//   tracks.csv    as `tactile capture --csv` writes it (each point once, when first seen)
//   edges.csv     as `tactile capture --csv` writes it
//   strain.h5     the strain movie (tactile capture's schema), growing frame by frame, with
//                 each camera frame's contact as judged when it came (frames dropped: unseen)
//   movie.h5      the frames sent to the display, at its rate (each camera frame held)
//   frames.mkv    every camera frame as received, dropped ones too (FFV1 in Matroska:
//                 lossless), stamped with its arrival time
// The CSV files are appended in whole lines; the HDF5 files grow through HDF5's single-writer
// mode (h5_growing.hpp), whose file on disk is whole at every moment. Everything is written and
// synced to the disk every half second on a thread of the recording's own (a sync can take tens
// of milliseconds, which the frames' path to the display must not wait for), so a session killed
// at any moment, SIGKILL or power cut included, leaves files the project's readers open,
// holding everything up to at most a second before the kill. At the end (the source's end,
// --seconds or Ctrl-C) finish() writes the rest and closes the files.
//
// The folder must be new or empty; its files are created new (never through a link planted
// there).

#include <cstdint>
#include <filesystem>
#include <memory>

#include "tactile/live/live_session.hpp"

namespace tactile::live {

// The strain frames a session measured, and of them those strain.h5 does not hold: its frames
// are of one span (one camera frame), so one measured across a dropped frame is in edges.csv
// only.
struct RecordedStrain {
  std::int64_t measured = 0;
  std::int64_t left_out_of_h5 = 0;
};

class SessionRecording {
 public:
  // Creates the folder and the three CSV files with their headers and starts the writer; throws
  // std::runtime_error naming the path and the OS's reason.
  explicit SessionRecording(const std::filesystem::path& dir);
  // Finishes as finish() does, reporting nothing.
  ~SessionRecording();
  SessionRecording(const SessionRecording&) = delete;
  SessionRecording& operator=(const SessionRecording&) = delete;

  // `callbacks` made to record into this too (each still calls what it called before). The
  // HDF5 files are created on the session's `started`.
  void attach(LiveCallbacks& callbacks);

  // Writes what is left, closes every file and stops the writer. Throws std::runtime_error
  // naming the file when a write failed during the session or now (what was written before
  // the failure stays).
  void finish();
  // After finish(): what became of the strain frames.
  RecordedStrain strain_frames() const;

 private:
  struct Writer;
  std::unique_ptr<Writer> writer_;
};

}  // namespace tactile::live
