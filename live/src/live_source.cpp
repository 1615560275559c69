#include "live_source.hpp"

#include <fmt/format.h>

#include <stdlib.h>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <opencv2/videoio.hpp>
#include <optional>
#include <thread>

#include "tactile/capture/capture_run.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/error.hpp"

namespace tactile::live {

namespace {

constexpr int kStreamOpenTimeoutMs = 10000;
constexpr int kStreamReadTimeoutMs = 2000;

// Frames at hand (a file, a folder, memory) handed over one by one as a camera would: frame k
// at start + k / rate, or when it is ready if later.
class Paced : public FrameSource {
 public:
  bool next(SourceFrame& out) final {
    if (!read(out.image)) return false;
    out.index = index_++;
    // Read ahead of its time, then held until then.
    std::this_thread::sleep_until(start_ +
                                  std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(out.index / rate_hz_)));
    // Handed over now: at its time, or later when reading it took longer than a frame.
    out.available = Clock::now();
    return true;
  }
  double rate_hz() const final { return rate_hz_; }

 protected:
  explicit Paced(Clock::time_point start) : start_(start) {}
  // The next frame, or false after the last.
  virtual bool read(capture::GrayImage& image) = 0;
  double rate_hz_ = capture::kCameraRateHz;

 private:
  Clock::time_point start_;
  std::int64_t index_ = 0;
};

class Rehearsal final : public Paced {
 public:
  Rehearsal(const std::string& source, std::optional<double> rate_hz, Clock::time_point start)
      : Paced(start), source_(source), frames_(source, 0, std::nullopt) {
    if (const std::string range = frames_.range_error(); !range.empty()) {
      throw FormatError(fmt::format("{}: no frames to play", source));
    }
    rate_hz_ =
        rate_hz.value_or(frames_.is_video() ? frames_.frame_rate_hz() : capture::kCameraRateHz);
  }
  std::string describe() const override {
    return fmt::format("{}: {} frames played at {:g} Hz", source_, frames_.count(), rate_hz_);
  }

 private:
  bool read(capture::GrayImage& image) override { return frames_.next(image); }
  std::string source_;
  capture::FrameRange frames_;
};

class InMemory final : public Paced {
 public:
  InMemory(const std::vector<capture::GrayImage>& frames, double rate_hz, Clock::time_point start)
      : Paced(start), frames_(frames) {
    rate_hz_ = rate_hz;
  }
  std::string describe() const override {
    return fmt::format("{} frames in memory played at {:g} Hz", frames_.size(), rate_hz_);
  }

 private:
  bool read(capture::GrayImage& image) override {
    if (read_ >= frames_.size()) return false;
    image = frames_[read_++];
    return true;
  }
  const std::vector<capture::GrayImage>& frames_;
  std::size_t read_ = 0;
};

class Device final : public FrameSource {
 public:
  Device(const std::string& source, std::optional<double> rate_hz)
      : source_(source), camera_(source.rfind("/dev/", 0) == 0) {
    bool opened = false;
    if (camera_) {
      opened = capture_.open(source, cv::CAP_V4L2);
    } else {
      // FFmpeg reads a second or more of a stream to learn its format before the first frame
      // (5 MB or 5 s by default); the frames read meanwhile then come out at once, a burst the
      // drop-oldest queue would mostly drop. A stream says its size and codec in its first
      // packets, so a short look is enough, unless the user set FFmpeg's options themselves.
      ::setenv("OPENCV_FFMPEG_CAPTURE_OPTIONS", "probesize;65536|analyzeduration;200000", 0);
      // A stream that stops sending ends the session within a bound (and lets a stop request
      // end it), instead of FFmpeg's 30 s.
      opened = capture_.open(source, cv::CAP_FFMPEG,
                             {cv::CAP_PROP_OPEN_TIMEOUT_MSEC, kStreamOpenTimeoutMs,
                              cv::CAP_PROP_READ_TIMEOUT_MSEC, kStreamReadTimeoutMs});
    }
    if (!opened) {
      throw FormatError(
          camera_
              ? fmt::format("{}: cannot open it as a V4L2 camera", source)
              : fmt::format("{}: cannot open it as a video stream (nothing readable within {} s)",
                            source, kStreamOpenTimeoutMs / 1000));
    }
    if (rate_hz && camera_) capture_.set(cv::CAP_PROP_FPS, *rate_hz);
    asked_hz_ = rate_hz;
    rate_hz_ = capture_.get(cv::CAP_PROP_FPS);
    if (!(rate_hz_ > 0 && rate_hz_ < 1e5)) rate_hz_ = rate_hz.value_or(capture::kCameraRateHz);
    width_px_ = static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_WIDTH));
    height_px_ = static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_HEIGHT));
  }
  bool next(SourceFrame& out) override {
    cv::Mat frame;
    if (!capture_.read(frame) || frame.empty()) {
      if (camera_) {
        throw FormatError(
            fmt::format("{}: the camera gave no frame after frame {} (removed or "
                        "stopped?)",
                        source_, index_));
      }
      return false;  // a stream's end, or nothing from it for kStreamReadTimeoutMs
    }
    out.available = Clock::now();
    out.driver_stamped = false;
    if (camera_) {
      if (const auto stamped = driver_time(capture_.get(cv::CAP_PROP_POS_MSEC), out.available)) {
        out.available = *stamped;
        out.driver_stamped = true;
      }
    }
    cv::Mat grey;
    if (frame.channels() == 1) {
      grey = frame;
    } else {
      cv::cvtColor(frame, grey, frame.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
    }
    if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U);
    out.image.width_px = grey.cols;
    out.image.height_px = grey.rows;
    out.image.pixels.assign(grey.datastart, grey.dataend);
    if (!grey.isContinuous()) {
      out.image.pixels.resize(static_cast<std::size_t>(grey.cols) * grey.rows);
      for (int r = 0; r < grey.rows; ++r) {
        std::copy_n(grey.ptr<std::uint8_t>(r), grey.cols,
                    out.image.pixels.data() + static_cast<std::size_t>(r) * grey.cols);
      }
    }
    out.index = index_++;
    return true;
  }
  double rate_hz() const override { return rate_hz_; }
  std::string describe() const override {
    return fmt::format("{}: {} x {} px at {:g} Hz{}", source_, width_px_, height_px_, rate_hz_,
                       asked_hz_ ? fmt::format(" (asked for {:g} Hz)", *asked_hz_) : "");
  }

 private:
  std::string source_;
  bool camera_ = false;
  cv::VideoCapture capture_;
  std::optional<double> asked_hz_;
  double rate_hz_ = 0;
  int width_px_ = 0, height_px_ = 0;
  std::int64_t index_ = 0;
};

}  // namespace

std::unique_ptr<FrameSource> open_rehearsal(const std::string& source,
                                            std::optional<double> rate_hz,
                                            Clock::time_point start) {
  return std::make_unique<Rehearsal>(source, rate_hz, start);
}

std::unique_ptr<FrameSource> open_in_memory(const std::vector<capture::GrayImage>& frames,
                                            double rate_hz, Clock::time_point start) {
  return std::make_unique<InMemory>(frames, rate_hz, start);
}

std::optional<Clock::time_point> driver_time(double pos_msec, Clock::time_point arrival) {
  if (!(pos_msec > 0) || !std::isfinite(pos_msec)) return std::nullopt;
  const Clock::time_point stamped{std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double, std::milli>(pos_msec))};
  if (stamped > arrival || arrival - stamped > std::chrono::seconds(1)) return std::nullopt;
  return stamped;
}

std::unique_ptr<FrameSource> open_device(const std::string& source, std::optional<double> rate_hz) {
  return std::make_unique<Device>(source, rate_hz);
}

}  // namespace tactile::live
