// A rendered window image as a PNG (viewer.hpp).
#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tactile/common/image_write.hpp"
#include "tactile/display/viewer.hpp"

namespace tactile::display {

void write_png(const std::filesystem::path& png, const RenderedImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw std::invalid_argument("screenshot: the image is empty or inconsistent");
  }
  // OpenCV wants BGR; the image is RGB.
  const cv::Mat rgb(image.height, image.width, CV_8UC3,
                    const_cast<std::uint8_t*>(image.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  write_image_atomically(png, bgr);
}

}  // namespace tactile::display
