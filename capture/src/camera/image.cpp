#include "tactile/capture/image.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "camera/cv_image.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/image_write.hpp"

namespace tactile::capture {

GrayImage read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw FormatError(fmt::format("{}: no such image file", path.string()));
  }
  if (std::filesystem::file_size(path, ec) == 0) {
    throw FormatError(fmt::format("{}: image file is empty", path.string()));
  }
  // imread returns an empty matrix on decode failure but may also print to stderr; reading the
  // bytes ourselves and decoding keeps the failure in our hands.
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    throw FormatError(
        fmt::format("{}: not a readable image ({})", path.string(), *opencv_error_text(e)));
  }
  if (decoded.empty()) {
    throw FormatError(
        fmt::format("{}: not a readable image (unknown or corrupt format)", path.string()));
  }
  return from_mat(decoded);
}

std::optional<std::string> opencv_error_text(const std::exception& e) {
  const auto* cv_error = dynamic_cast<const cv::Exception*>(&e);
  if (cv_error == nullptr) return std::nullopt;
  // The one limit a user meets in practice, in its own words.
  if (cv_error->err.find("CV_IO_MAX_IMAGE_PIXELS") != std::string::npos) {
    return "the image has more pixels than OpenCV decodes (2^30)";
  }
  return fmt::format("image processing failed in OpenCV's {}: {}",
                     cv_error->func.empty() ? std::string("code") : cv_error->func, cv_error->err);
}

void write_png(const std::filesystem::path& path, const GrayImage& image) {
  write_image_atomically(path, as_mat(image));
}

namespace {
bool is_image_name(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff";
}
}  // namespace

std::vector<std::filesystem::path> list_frames(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw FormatError(fmt::format("{}: not a directory of frames", dir.string()));
  }
  std::vector<std::filesystem::path> frames;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.is_regular_file() && is_image_name(entry.path())) frames.push_back(entry.path());
  }
  if (frames.empty()) {
    throw FormatError(fmt::format(
        "{}: no image files (.png .jpg .jpeg .bmp .tif) in this directory", dir.string()));
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

std::vector<GrayImage> read_frames(const std::filesystem::path& dir) {
  const auto paths = list_frames(dir);
  std::vector<GrayImage> frames;
  frames.reserve(paths.size());
  for (const auto& path : paths) {
    GrayImage image = read_image(path);
    if (!frames.empty() && (image.width_px != frames.front().width_px ||
                            image.height_px != frames.front().height_px)) {
      throw FormatError(fmt::format(
          "{}: frame is {}x{} px but {} is {}x{} px; all frames of a "
          "sequence must have the same size",
          path.string(), image.width_px, image.height_px, paths.front().filename().string(),
          frames.front().width_px, frames.front().height_px));
    }
    frames.push_back(std::move(image));
  }
  return frames;
}

std::string frame_file_name(std::size_t i) {
  return fmt::format("frame_{:03d}.png", i);
}

void write_frames(const std::filesystem::path& dir, const std::vector<GrayImage>& frames) {
  std::filesystem::create_directories(dir);
  for (std::size_t i = 0; i < frames.size(); ++i) write_png(dir / frame_file_name(i), frames[i]);
}

}  // namespace tactile::capture
