#include "tactile/capture/contact_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "../camera/cv_image.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {

namespace {

// A fingertip's ridges repeat every 0.4-0.5 mm; a box of one period's side averages them out,
// leaving the local mean (the illumination and the skin's brightness) to subtract.
constexpr double kRidgePeriodMm = 0.45;

int cells_over(int side_px, int cell_px) {
  return (side_px + cell_px - 1) / cell_px;
}

}  // namespace

ContactGrid contact_grid(int width_px, int height_px, double px_per_mm) {
  if (width_px < 1 || height_px < 1 || !(px_per_mm > 0) || !std::isfinite(px_per_mm)) {
    throw std::invalid_argument(
        fmt::format("contact_grid: an image of {} x {} px at {} px/mm has no cells", width_px,
                    height_px, px_per_mm));
  }
  return contact_grid_of_cells(
      width_px, height_px, static_cast<std::int32_t>(std::clamp(std::lround(px_per_mm), 8L, 256L)));
}

ContactGrid contact_grid_of_cells(int width_px, int height_px, std::int32_t cell_px) {
  return {cell_px, cells_over(width_px, cell_px), cells_over(height_px, cell_px)};
}

std::vector<double> cell_ridge_contrast(const GrayImage& frame, const ContactGrid& grid,
                                        double px_per_mm) {
  const ContactGrid fits = contact_grid_of_cells(frame.width_px, frame.height_px, grid.cell_px);
  if (fits.columns != grid.columns || fits.rows != grid.rows) {
    throw std::invalid_argument(fmt::format(
        "cell_ridge_contrast: a {} x {} px frame does not fit a grid of {} x {} cells of {} px",
        frame.width_px, frame.height_px, grid.columns, grid.rows, grid.cell_px));
  }
  // Ridges of 0.4-0.5 mm are still sampled several times a period at half the resolution when a
  // cell is 16 px or more (about 16 px/mm and up): there the work is a quarter, and the cells'
  // contrasts the same up to the camera noise that the averaging of four pixels removes.
  const int scale = grid.cell_px >= 16 ? 2 : 1;
  cv::Mat image;
  if (scale == 2) {
    cv::Mat half;
    cv::resize(as_mat(frame), half, {(frame.width_px + 1) / 2, (frame.height_px + 1) / 2}, 0, 0,
               cv::INTER_AREA);
    half.convertTo(image, CV_32F);
  } else {
    as_mat(frame).convertTo(image, CV_32F);
  }
  const int box =
      std::max(3, static_cast<int>(std::lround(kRidgePeriodMm * px_per_mm / scale)) | 1);
  cv::Mat mean;
  cv::blur(image, mean, {box, box}, {-1, -1}, cv::BORDER_REFLECT);
  cv::Mat detail = image - mean;
  cv::Mat squared = detail.mul(detail);
  std::vector<double> contrast(static_cast<std::size_t>(grid.cells()));
  const cv::Rect whole(0, 0, image.cols, image.rows);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.columns; ++c) {
      const int x0 = c * grid.cell_px / scale, y0 = r * grid.cell_px / scale;
      const int x1 = (c + 1) * grid.cell_px / scale, y1 = (r + 1) * grid.cell_px / scale;
      const cv::Rect cell = cv::Rect(x0, y0, x1 - x0, y1 - y0) & whole;
      contrast[static_cast<std::size_t>(r * grid.columns + c)] =
          std::sqrt(cv::mean(squared(cell))[0]);
    }
  }
  return contrast;
}

ContactMap contact_map(const ContactGrid& grid, std::vector<double> ridge_contrast) {
  if (grid.cells() <= 0 || ridge_contrast.size() % static_cast<std::size_t>(grid.cells()) != 0) {
    throw std::invalid_argument(
        fmt::format("contact_map: {} cell contrasts are not whole frames of {} cells",
                    ridge_contrast.size(), grid.cells()));
  }
  ContactMap map;
  map.grid = grid;
  map.threshold = std::max(kContactFloorGrey, kContactFraction * quantile(ridge_contrast, 0.9));
  map.in_contact.reserve(ridge_contrast.size());
  for (const double c : ridge_contrast) map.in_contact.push_back(c >= map.threshold ? 1 : 0);
  map.ridge_contrast = std::move(ridge_contrast);
  return map;
}

ContactMap measure_contact(const std::vector<GrayImage>& frames, double px_per_mm) {
  if (frames.empty()) return {};
  const ContactGrid grid = contact_grid(frames[0].width_px, frames[0].height_px, px_per_mm);
  std::vector<double> contrast;
  for (const auto& frame : frames) {
    const auto cells = cell_ridge_contrast(frame, grid, px_per_mm);
    contrast.insert(contrast.end(), cells.begin(), cells.end());
  }
  return contact_map(grid, std::move(contrast));
}

std::vector<std::uint8_t> contact_of_frame(RunningContact& running,
                                           const std::vector<double>& ridge_contrast) {
  if (!ridge_contrast.empty()) {
    running.contact_contrast_grey =
        std::max(running.contact_contrast_grey, quantile(ridge_contrast, 0.9));
  }
  const double threshold = running_threshold_grey(running);
  std::vector<std::uint8_t> in_contact;
  in_contact.reserve(ridge_contrast.size());
  for (const double c : ridge_contrast) in_contact.push_back(c >= threshold ? 1 : 0);
  return in_contact;
}

double running_threshold_grey(const RunningContact& running) {
  return std::max(kContactFloorGrey, kContactFraction * running.contact_contrast_grey);
}

double contact_fraction(const ContactMap& map, std::int32_t frame) {
  if (!map.measured() || frame < 0 || frame >= map.frame_count()) return 0;
  const auto cells = static_cast<std::ptrdiff_t>(map.grid.cells());
  const auto first = map.in_contact.begin() + frame * cells;
  return static_cast<double>(std::count(first, first + cells, std::uint8_t{1})) /
         static_cast<double>(cells);
}

}  // namespace tactile::capture
