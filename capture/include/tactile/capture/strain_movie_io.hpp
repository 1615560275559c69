#pragma once
// Strain movie files: HDF5 with the schema in capture/FORMAT.md, and CSV export.

#include <filesystem>
#include <string>
#include <string_view>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

inline constexpr const char* kStrainMovieFormat = "tactile-strain-movie";
inline constexpr int kStrainMovieFormatVersion = 1;

// Writes atomically: an existing file is replaced only when the new one is complete.
void write_strain_movie(const std::filesystem::path& path, const StrainMovie& movie);

// Throws tactile::FormatError naming the file, the object and the problem: missing file, not
// HDF5, another format or version, missing groups/datasets/attributes, wrong types or ranks,
// inconsistent sizes or references (e.g. an edge naming a track that does not exist).
StrainMovie read_strain_movie(const std::filesystem::path& path);

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
