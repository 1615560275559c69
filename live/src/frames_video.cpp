// FramesVideo; see frames_video.hpp.

#include "frames_video.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/opt.h>
}

namespace tactile::live {

namespace {

std::string av_message(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

// libavformat writes through these into a descriptor we opened ourselves (O_EXCL, O_NOFOLLOW),
// which its own file protocol cannot promise.
int write_packet(void* opaque, std::uint8_t* data, int size) {
  const int fd = *static_cast<int*>(opaque);
  int done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, static_cast<std::size_t>(size - done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return AVERROR(errno);
    done += static_cast<int>(n);
  }
  return size;
}

std::int64_t seek(void* opaque, std::int64_t offset, int whence) {
  const int fd = *static_cast<int*>(opaque);
  if (whence == AVSEEK_SIZE) {
    struct stat st {};
    return ::fstat(fd, &st) == 0 ? st.st_size : AVERROR(errno);
  }
  const off_t at = ::lseek(fd, offset, whence & ~AVSEEK_FORCE);
  return at < 0 ? AVERROR(errno) : at;
}

}  // namespace

struct FramesVideo::Impl {
  std::filesystem::path path;
  int fd = -1;
  int width_px = 0, height_px = 0;
  std::int64_t last_pts = -1;
  AVFormatContext* format = nullptr;
  AVIOContext* io = nullptr;
  AVCodecContext* encoder = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  bool header_written = false;
  bool closed = false;

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw std::runtime_error(
        fmt::format("cannot write {}: {}: {}", path.string(), what, av_message(code)));
  }

  // Sends `f` (nullptr: the end) to the encoder and writes every packet it gives.
  void encode(const AVFrame* f) {
    int rc = avcodec_send_frame(encoder, f);
    if (rc < 0) fail("encoding a frame", rc);
    while ((rc = avcodec_receive_packet(encoder, packet)) == 0) {
      av_packet_rescale_ts(packet, encoder->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_write_frame(format, packet);
      av_packet_unref(packet);
      if (rc < 0) fail("writing a frame", rc);
    }
    if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) fail("encoding a frame", rc);
  }

  void release() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&encoder);
    if (io != nullptr) {
      av_freep(&io->buffer);
      avio_context_free(&io);
    }
    if (format != nullptr) {
      format->pb = nullptr;
      avformat_free_context(format);
      format = nullptr;
    }
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

FramesVideo::FramesVideo(const std::filesystem::path& path, int width_px, int height_px,
                         double rate_hz)
    : impl_(std::make_unique<Impl>()) {
  Impl& v = *impl_;
  v.path = path;
  v.width_px = width_px;
  v.height_px = height_px;
  v.fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (v.fd < 0) {
    throw std::runtime_error(
        fmt::format("cannot create {}: {}", path.string(), std::strerror(errno)));
  }
  try {
    int rc = avformat_alloc_output_context2(&v.format, nullptr, "matroska", nullptr);
    if (rc < 0) v.fail("no Matroska muxer", rc);
    const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_FFV1);
    if (codec == nullptr) v.fail("no FFV1 encoder", AVERROR_ENCODER_NOT_FOUND);
    v.stream = avformat_new_stream(v.format, nullptr);
    v.encoder = avcodec_alloc_context3(codec);
    v.frame = av_frame_alloc();
    v.packet = av_packet_alloc();
    if (v.stream == nullptr || v.encoder == nullptr || v.frame == nullptr || v.packet == nullptr) {
      v.fail("out of memory", AVERROR(ENOMEM));
    }
    v.encoder->width = width_px;
    v.encoder->height = height_px;
    v.encoder->pix_fmt = AV_PIX_FMT_GRAY8;
    // Milliseconds: frames are stamped with when they arrived.
    v.encoder->time_base = AVRational{1, 1000};
    v.encoder->framerate = av_d2q(rate_hz, 100000);
    v.encoder->gop_size = 1;
    if ((v.format->oformat->flags & AVFMT_GLOBALHEADER) != 0) {
      v.encoder->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    }
    rc = avcodec_open2(v.encoder, codec, nullptr);
    if (rc < 0) v.fail("opening the FFV1 encoder", rc);
    rc = avcodec_parameters_from_context(v.stream->codecpar, v.encoder);
    if (rc < 0) v.fail("stream parameters", rc);
    v.stream->time_base = v.encoder->time_base;
    v.stream->avg_frame_rate = v.encoder->framerate;

    constexpr int kBufferBytes = 64 * 1024;
    auto* buffer = static_cast<unsigned char*>(av_malloc(kBufferBytes));
    v.io = avio_alloc_context(buffer, kBufferBytes, 1, &v.fd, nullptr, write_packet, seek);
    if (v.io == nullptr) {
      av_free(buffer);
      v.fail("out of memory", AVERROR(ENOMEM));
    }
    v.format->pb = v.io;
    v.format->flags |= AVFMT_FLAG_CUSTOM_IO;
    AVDictionary* options = nullptr;
    // A cluster closes every half second at the latest even between our flushes.
    av_dict_set(&options, "cluster_time_limit", "500", 0);
    rc = avformat_write_header(v.format, &options);
    av_dict_free(&options);
    if (rc < 0) v.fail("writing the header", rc);
    v.header_written = true;

    v.frame->format = AV_PIX_FMT_GRAY8;
    v.frame->width = width_px;
    v.frame->height = height_px;
    rc = av_frame_get_buffer(v.frame, 0);
    if (rc < 0) v.fail("a frame buffer", rc);
  } catch (...) {
    v.release();
    throw;
  }
}

FramesVideo::~FramesVideo() {
  try {
    close();
  } catch (const std::exception&) {
    // A destructor cannot report; close() called before it does.
  }
  impl_->release();
}

void FramesVideo::write(const capture::GrayImage& image, double time_s) {
  Impl& v = *impl_;
  if (image.width_px != v.width_px || image.height_px != v.height_px) {
    throw std::runtime_error(
        fmt::format("cannot write {}: a frame of {} x {} px in a video of {} x {} px",
                    v.path.string(), image.width_px, image.height_px, v.width_px, v.height_px));
  }
  const int rc = av_frame_make_writable(v.frame);
  if (rc < 0) v.fail("a frame buffer", rc);
  for (int y = 0; y < v.height_px; ++y) {
    std::memcpy(v.frame->data[0] + static_cast<std::ptrdiff_t>(y) * v.frame->linesize[0],
                image.pixels.data() + static_cast<std::size_t>(y) * v.width_px,
                static_cast<std::size_t>(v.width_px));
  }
  // Strictly increasing, as a container needs, even for frames within a millisecond.
  v.last_pts = std::max(v.last_pts + 1, static_cast<std::int64_t>(std::llround(time_s * 1000)));
  v.frame->pts = v.last_pts;
  v.encode(v.frame);
}

void FramesVideo::flush() {
  Impl& v = *impl_;
  // A null packet ends the Matroska cluster being filled, which then reaches our descriptor.
  const int rc = av_write_frame(v.format, nullptr);
  if (rc < 0) v.fail("flushing", rc);
  avio_flush(v.io);
  if (v.io->error < 0) v.fail("flushing", v.io->error);
  ::fdatasync(v.fd);
}

void FramesVideo::close() {
  Impl& v = *impl_;
  if (v.closed || !v.header_written) return;
  v.closed = true;
  v.encode(nullptr);
  const int rc = av_write_trailer(v.format);
  if (rc < 0) v.fail("writing the index", rc);
  avio_flush(v.io);
  ::fdatasync(v.fd);
}

}  // namespace tactile::live
