#pragma once
// Strain movie files: HDF5 with the schema in capture/FORMAT.md, and CSV export.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/h5_growing.hpp"

namespace tactile::h5 {
class ReadingProcess;
}  // namespace tactile::h5

namespace tactile::capture {

inline constexpr const char* kStrainMovieFormat = "tactile-strain-movie";
inline constexpr int kStrainMovieFormatVersion = 1;

// Writes atomically: an existing file is replaced only when the new one is complete.
void write_strain_movie(const std::filesystem::path& path, const StrainMovie& movie);

// A strain movie written as it is measured, into a file that the reader below opens at every
// moment, a kill or a power cut included, holding every frame up to the last flush(). The
// header (rate, span, calibration, field, provenance) is `header`'s; its tracks and frames are
// ignored. Strain frames of another span than the header's are left out. /tracks is in the
// order points were first seen (by frame), not by track as write_strain_movie orders it; the
// reader takes either. Creates `path` new (never over a file or through a link).
// With a contact grid in the header (`header.contact.grid`), the file holds a contact map of
// frame thresholds (ContactMap::frame_threshold): each camera frame's cells given to
// append_contact, or marked unseen, in any order; a frame is written once every frame before it
// is known, and close() marks the frames never given as unseen.
class StrainMovieAppender {
 public:
  StrainMovieAppender(const std::filesystem::path& path, const StrainMovie& header);
  ~StrainMovieAppender();
  StrainMovieAppender(const StrainMovieAppender&) = delete;
  StrainMovieAppender& operator=(const StrainMovieAppender&) = delete;

  // Keeps `frame` for the next flush; returns the points that became new rows of /tracks.
  std::vector<TrackedPoint> append(const StrainFrame& frame);
  // Camera frame `frame`'s cells (rows x columns of the header's contact grid), judged by
  // `threshold_grey`; or the frame was dropped unseen. Ignored without a contact grid, or for a
  // frame already written.
  void append_contact(std::int64_t frame, double threshold_grey, std::vector<double> ridge_contrast,
                      std::vector<std::uint8_t> in_contact);
  void append_unseen(std::int64_t frame);
  // Writes what was appended since the last flush and syncs it to the disk.
  void flush();
  // Flushes and closes: the file is then as any other strain movie.
  void close();
  // The strain frames appended so far that were left out for their span.
  std::int64_t frames_left_out() const { return frames_left_out_; }

 private:
  struct Columns;
  // A camera frame's contact, held until every frame before it is known.
  struct ContactRow {
    double threshold_grey = 0;
    bool seen = false;
    std::vector<double> ridge_contrast;
    std::vector<std::uint8_t> in_contact;
  };
  void take_held_contact();
  h5::GrowingFile file_;
  std::unique_ptr<Columns> pending_;
  std::int32_t span_frames_ = 1;
  std::int64_t last_frame_ = -1;
  std::unordered_set<std::int32_t> last_to_tracks_;
  std::int64_t camera_frame_count_ = 0;
  std::int64_t frames_left_out_ = 0;
  ContactGrid contact_grid_;
  std::int64_t contact_frames_ = 0;  // camera frames of the contact map in the columns or file
  std::map<std::int64_t, ContactRow> held_contact_;
};

// Throws tactile::FormatError naming the file, the object and the problem: missing file, not
// HDF5, another format or version, missing groups/datasets/attributes, wrong types or ranks,
// inconsistent sizes or references (e.g. an edge naming a track that does not exist).
// The file is read first in a child process (h5::read_in_child_first): `process`, when given,
// is one kept for many files (h5::ReadingProcess); else one is forked for this file.
StrainMovie read_strain_movie(const std::filesystem::path& path,
                              h5::ReadingProcess* process = nullptr);

// Writes dir/tracks.csv (track_id,frame,type,x_px,y_px,x_mm,y_mm) and dir/edges.csv
// (frame_from,frame_to,track_a,track_b,length_from_mm,length_to_mm,rel_change); creates dir.
void export_strain_csv(const std::filesystem::path& dir, const StrainMovie& movie);

// The rows of those two files (each line ending in a newline), for writers that append them as
// they go (a live session's recording).
inline constexpr std::string_view kTracksCsvHeader = "track_id,frame,type,x_px,y_px,x_mm,y_mm";
inline constexpr std::string_view kEdgesCsvHeader =
    "frame_from,frame_to,track_a,track_b,length_from_mm,length_to_mm,rel_change";
std::string tracks_csv_row(const TrackedPoint& point);
std::string edges_csv_rows(const StrainFrame& frame);

}  // namespace tactile::capture
