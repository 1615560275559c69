#pragma once
// Where a live session's frames come from: a camera or stream read as the frames arrive, or a
// file or folder played at its frame rate as a camera would deliver it.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/live/driver_time.hpp"
#include "tactile/live/live_session.hpp"

namespace tactile::live {

struct SourceFrame {
  std::int64_t index = 0;
  capture::GrayImage image;
  // Scheduled time (rehearsal); a camera's driver timestamp where it gives a plausible one, else
  // arrival (camera, stream).
  Clock::time_point available;
  bool driver_stamped = false;  // `available` is the driver's timestamp
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame, waiting until it is available; false after the last one. Throws
  // tactile::FormatError naming the source when it cannot be read (a camera that went away).
  virtual bool next(SourceFrame& out) = 0;
  virtual double rate_hz() const = 0;
  // What the source is and what it granted ("/dev/video0: 640 x 480 at 60 Hz (asked 120 Hz)").
  virtual std::string describe() const = 0;
};

// A file or folder played at `rate_hz` (unset: a video's own rate, else the default camera
// rate) from `start` on.
std::unique_ptr<FrameSource> open_rehearsal(const std::string& source,
                                            std::optional<double> rate_hz, Clock::time_point start);
// A camera (/dev/videoN, asked for `rate_hz` when given) or a stream URL, through OpenCV's
// videoio (V4L2, FFmpeg).
std::unique_ptr<FrameSource> open_device(const std::string& source, std::optional<double> rate_hz);

// Frames held in memory, handed over at `rate_hz` from `start` on as a camera would (a bench
// measures the session without the cost of decoding files, which a camera does not have).
std::unique_ptr<FrameSource> open_in_memory(const std::vector<capture::GrayImage>& frames,
                                            double rate_hz, Clock::time_point start);

// run_live on a source already opened, whose frames are timed from `start`.
LiveSummary run_live_from(FrameSource& source, Clock::time_point start, const ResolvedLive& session,
                          display::Transport& device, const std::atomic<bool>& stop,
                          const LiveCallbacks& callbacks, const LiveOptions& options);

}  // namespace tactile::live
