#include "tactile/capture/video.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "camera/cv_image.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {

bool is_video_name(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".mp4" || ext == ".avi" || ext == ".mkv" || ext == ".mov";
}

struct VideoReader::State {
  std::filesystem::path path;
  cv::VideoCapture capture;
  VideoInfo info;
  int position = 0;
  cv::Mat decoded;
};

namespace {

// Ten hours at 240 Hz: beyond it, a count by reading is stopped.
constexpr int kMaxCountedFrames = 8640000;

}  // namespace

VideoReader::VideoReader(const std::filesystem::path& path) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw FormatError(fmt::format("{}: no such video file", path.string()));
  }
  if (!s.capture.open(path.string(), cv::CAP_FFMPEG) || !s.capture.isOpened()) {
    throw FormatError(fmt::format(
        "{}: cannot be opened as a video (not a video, damaged, or a codec FFmpeg lacks)",
        path.string()));
  }
  s.info.width_px = static_cast<int>(s.capture.get(cv::CAP_PROP_FRAME_WIDTH));
  s.info.height_px = static_cast<int>(s.capture.get(cv::CAP_PROP_FRAME_HEIGHT));
  s.info.frame_rate_hz = s.capture.get(cv::CAP_PROP_FPS);
  const double count = s.capture.get(cv::CAP_PROP_FRAME_COUNT);
  s.info.frame_count = count >= 1 && count < 1e9 ? static_cast<int>(std::lround(count)) : 0;
  if (s.info.width_px < 1 || s.info.height_px < 1) {
    throw FormatError(fmt::format("{}: the video states no frame size", path.string()));
  }
  if (!(s.info.frame_rate_hz > 0 && std::isfinite(s.info.frame_rate_hz))) {
    throw FormatError(fmt::format("{}: the video states no frame rate", path.string()));
  }
  if (s.info.frame_count < 1) {
    // A file cut short (a live recording's frames.mkv after a kill) has no index stating its
    // length: counted by reading it through once, then read again from the start.
    int counted = 0;
    while (counted < kMaxCountedFrames && s.capture.grab()) ++counted;
    s.info.frame_count = counted;
    if (counted < 1 || !s.capture.open(path.string(), cv::CAP_FFMPEG)) {
      throw FormatError(
          fmt::format("{}: the video states no frames and none can be read", path.string()));
    }
  }
}

VideoReader::~VideoReader() = default;

const VideoInfo& VideoReader::info() const {
  return state_->info;
}

int VideoReader::position() const {
  return state_->position;
}

void VideoReader::skip_to(int index) {
  GrayImage dropped;
  while (state_->position < index && read(dropped)) {
  }
}

bool VideoReader::read(GrayImage& frame) {
  State& s = *state_;
  if (s.position >= s.info.frame_count) return false;
  if (!s.capture.read(s.decoded) || s.decoded.empty()) {
    throw FormatError(fmt::format(
        "{}: frame {} cannot be decoded, but the video states {} frames (truncated or damaged "
        "file)",
        s.path.string(), s.position, s.info.frame_count));
  }
  if (s.decoded.cols != s.info.width_px || s.decoded.rows != s.info.height_px) {
    throw FormatError(fmt::format("{}: frame {} is {}x{} px, the video states {}x{} px",
                                  s.path.string(), s.position, s.decoded.cols, s.decoded.rows,
                                  s.info.width_px, s.info.height_px));
  }
  cv::Mat grey;
  if (s.decoded.channels() == 1) {
    grey = s.decoded;
  } else {
    cv::cvtColor(s.decoded, grey,
                 s.decoded.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  }
  if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U);
  frame = from_mat(grey);
  ++s.position;
  return true;
}

void write_lossless_video(const std::filesystem::path& path, const std::vector<GrayImage>& frames,
                          double frame_rate_hz) {
  if (frames.empty()) throw FormatError(fmt::format("{}: no frames to write", path.string()));
  const cv::Size size(frames.front().width_px, frames.front().height_px);
  cv::VideoWriter writer(path.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('F', 'F', 'V', '1'),
                         frame_rate_hz, size, false);
  if (!writer.isOpened()) {
    throw FormatError(fmt::format("{}: cannot be written as an FFV1 video", path.string()));
  }
  for (const auto& frame : frames) {
    if (frame.width_px != size.width || frame.height_px != size.height) {
      throw FormatError(fmt::format("{}: frames of {}x{} px and {}x{} px in one video",
                                    path.string(), size.width, size.height, frame.width_px,
                                    frame.height_px));
    }
    writer.write(as_mat(frame));
  }
  writer.release();
}

}  // namespace tactile::capture
