#pragma once
// Frames of a video file (OpenCV videoio over FFmpeg), decoded one at a time so that a long video
// is never held in memory.

#include <filesystem>
#include <memory>
#include <vector>

#include "tactile/capture/image.hpp"

namespace tactile::capture {

// A name `tactile capture` reads as a video: .mp4 .avi .mkv .mov (any case).
bool is_video_name(const std::filesystem::path& path);

struct VideoInfo {
  int width_px = 0;
  int height_px = 0;
  double frame_rate_hz = 0;  // from the container
  int frame_count = 0;       // as the container states it
};

class VideoReader {
 public:
  // Opens `path`; throws tactile::FormatError naming the file when it cannot be opened or its
  // container gives no frame size, frame rate or frame count.
  explicit VideoReader(const std::filesystem::path& path);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  const VideoInfo& info() const;
  // Index of the frame the next read returns (0 = the video's first frame).
  int position() const;
  // Decodes and drops frames up to frame `index` (decoding, not container seeking, which lands
  // on key frames in some formats).
  void skip_to(int index);
  // The next frame in grey levels, or false after the container's last frame. Throws
  // tactile::FormatError naming the file and the frame when a frame the container announces
  // cannot be decoded (a truncated or damaged file) or has the wrong size.
  bool read(GrayImage& frame);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Writes `frames` (all of one size) as a lossless video: FFV1 in a Matroska (.mkv) file, at
// `frame_rate_hz`. Throws tactile::FormatError naming the file when it cannot be written.
void write_lossless_video(const std::filesystem::path& path, const std::vector<GrayImage>& frames,
                          double frame_rate_hz);

}  // namespace tactile::capture
