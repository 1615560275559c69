#pragma once
// The frames of a live session as received, into a Matroska file of FFV1 (lossless, every frame
// a key frame), written through libavformat so that the file can be flushed: each flush() ends
// the Matroska cluster being filled and puts everything on the disk, and a file cut after any
// flush (a kill, a power cut) is read to its last whole cluster by FFmpeg and so by OpenCV.

#include <cstdint>
#include <filesystem>
#include <memory>

#include "tactile/capture/image.hpp"

namespace tactile::live {

class FramesVideo {
 public:
  // Creates `path` new (never over a file or through a link) for frames of width x height px;
  // `rate_hz` is stored as the stream's nominal rate. Throws std::runtime_error naming `path`.
  FramesVideo(const std::filesystem::path& path, int width_px, int height_px, double rate_hz);
  ~FramesVideo();
  FramesVideo(const FramesVideo&) = delete;
  FramesVideo& operator=(const FramesVideo&) = delete;

  // One frame, at `time_s` from the session's start (times must increase). A frame of another
  // size than the first is refused (std::runtime_error): a stream does not change size.
  void write(const capture::GrayImage& image, double time_s);
  void flush();
  // Flushes, writes the file's index and closes it.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::live
