#pragma once
// An OpenCV image written through the project's one way of writing a file (atomic_write.hpp):
// encoded in memory, then written atomically, so that OpenCV never opens the destination itself.
// Header-only because common does not link OpenCV; the modules that draw images do.

#include <fmt/format.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "tactile/common/atomic_write.hpp"

namespace tactile {

// Writes `image` to `path` in the format its extension names (".png"). Throws
// std::runtime_error naming the path and the reason.
inline void write_image_atomically(const std::filesystem::path& path, const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  bool encoded = false;
  std::string why = "OpenCV cannot encode it";
  try {
    encoded = cv::imencode(path.extension().string(), image, bytes);
  } catch (const cv::Exception& e) {
    why = e.what();
  }
  if (!encoded) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), why));
  }
  write_atomically(path,
                   std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace tactile
