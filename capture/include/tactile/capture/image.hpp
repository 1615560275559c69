#pragma once
// 8-bit grey images as plain data, so that OpenCV stays out of the public headers.

#include <cstdint>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tactile::capture {

struct GrayImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> pixels;  // row-major, width_px * height_px bytes

  std::uint8_t at(int x_px, int y_px) const {
    return pixels[static_cast<std::size_t>(y_px) * static_cast<std::size_t>(width_px) +
                  static_cast<std::size_t>(x_px)];
  }
};

// Reads a PNG, JPEG, BMP, TIFF or WebP image (by its content, not its name), converted to grey.
// Throws tactile::FormatError naming the file and what is wrong if it is missing, empty, of
// another format, damaged or truncated; no library prints anything of its own.
GrayImage read_image(const std::filesystem::path& path);

// Writes a PNG; throws std::runtime_error naming the file on failure.
void write_png(const std::filesystem::path& path, const GrayImage& image);

// Image files (.png .jpg .jpeg .bmp .tif .tiff, any case) in `dir`, sorted by name.
// Throws tactile::FormatError if `dir` is not a directory or holds no image.
std::vector<std::filesystem::path> list_frames(const std::filesystem::path& dir);

// All frames of `dir` in name order. Throws tactile::FormatError naming the first file whose
// size differs from the first frame's.
std::vector<GrayImage> read_frames(const std::filesystem::path& dir);

// The file name of frame i as write_frames writes it: frame_000.png, frame_001.png, ...
std::string frame_file_name(std::size_t i);
// The files write_frames writes for `count` frames, first to last, as a folder's description
// names them: "frame_000.png .. frame_179.png".
std::string frame_files_text(std::size_t count);

// Writes frames under frame_file_name in `dir` (created if missing), the layout read_frames
// reads back in order.
void write_frames(const std::filesystem::path& dir, const std::vector<GrayImage>& frames);

// OpenCV's exceptions (cv::Exception, a std::exception whose text is a source path, a line and
// an assertion) said in a person's words: "image processing failed in OpenCV's resize: <what
// it checked>"; nullopt for any other exception. For the one place that reports failures (the
// program's main), which does not see OpenCV itself.
std::optional<std::string> opencv_error_text(const std::exception& e);

}  // namespace tactile::capture
