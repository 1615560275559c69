// Preview image strip drawn with OpenCV; see preview.hpp.
#include "tactile/display/preview.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tactile/common/image_write.hpp"
#include "tactile/display/summary.hpp"
#include "tactile/movie/frame_geometry.hpp"

namespace tactile::display {

namespace {

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrey(170, 170, 170);
const cv::Scalar kPlotBlue(180, 90, 20);  // BGR
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Scalar bgr(const std::array<std::uint8_t, 3>& rgb) {
  return cv::Scalar(rgb[2], rgb[1], rgb[0]);
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.4,
          const cv::Scalar& colour = kBlack) {
  cv::putText(img, s, at, kFont, scale, colour, 1, cv::LINE_AA);
}

void draw_panel(cv::Mat& panel, const movie::Layout& layout, std::span<const float> frame,
                double magnification, double strain_scale) {
  const movie::ViewTransform s = movie::fit_view(layout, magnification, panel.cols, panel.rows);
  for (const movie::ContactorShape& c : movie::frame_shapes(layout, frame, magnification)) {
    const cv::Point2d centre(s.origin_x_px + c.x_mm * s.px_per_mm,
                             s.origin_y_px + c.y_mm * s.px_per_mm);
    const cv::Point2d half(c.width_mm * s.px_per_mm / 2, c.height_mm * s.px_per_mm / 2);
    const cv::Rect box(cv::Point(static_cast<int>(std::lround(centre.x - half.x)),
                                 static_cast<int>(std::lround(centre.y - half.y))),
                       cv::Point(static_cast<int>(std::lround(centre.x + half.x)),
                                 static_cast<int>(std::lround(centre.y + half.y))));
    cv::rectangle(panel, box, bgr(movie::strain_colour(c.strain, strain_scale)), cv::FILLED);
    cv::rectangle(panel, box, kBlack, 1);
    // The rest position as a small grey cross, so displacement is visible in a still image.
    const cv::Point rest(static_cast<int>(std::lround(s.origin_x_px + c.rest_x_mm * s.px_per_mm)),
                         static_cast<int>(std::lround(s.origin_y_px + c.rest_y_mm * s.px_per_mm)));
    cv::drawMarker(panel, rest, kGrey, cv::MARKER_CROSS, 5, 1);
  }
}

void draw_header(cv::Mat& header, const movie::TactileMovie& movie, double magnification,
                 double strain_scale, int panel_px) {
  text(header,
       fmt::format("{} ({} x {}), {} frames at {} Hz, {:.2f} s", movie.layout.name,
                   movie.layout.rows, movie.layout.cols, movie.frame_count, movie.rate_hz,
                   movie.duration_s()),
       {8, 18}, 0.5);
  // Colour scale: compression (blue) .. stretch (red), in per cent as the viewer gives strain.
  const int bar_x = 8, bar_y = 30, bar_w = 160, bar_h = 12;
  for (int i = 0; i < bar_w; ++i) {
    const double s = (2.0 * i / (bar_w - 1) - 1.0) * strain_scale;
    cv::line(header, {bar_x + i, bar_y}, {bar_x + i, bar_y + bar_h},
             bgr(movie::strain_colour(s, strain_scale)));
  }
  cv::rectangle(header, {bar_x, bar_y, bar_w, bar_h}, kBlack, 1);
  text(header,
       fmt::format("strain -{0:.2f} % .. 0 .. +{0:.2f} % (blue compression, red stretch)",
                   strain_scale * 100),
       {bar_x + bar_w + 8, bar_y + 11});
  // Deflection scale bar: the layout's largest deflection at the panels' scale and
  // magnification, so the reader can judge every displacement against the full range.
  const double range_um =
      std::max(std::abs(movie.layout.deflection_min_um), std::abs(movie.layout.deflection_max_um));
  const movie::ViewTransform s = movie::fit_view(movie.layout, magnification, panel_px, panel_px);
  const int len =
      std::max(2, static_cast<int>(std::lround(range_um * magnification / 1000.0 * s.px_per_mm)));
  const int sx = header.cols - len - 190;
  if (sx > bar_x + bar_w + 8) {
    cv::line(header, {sx, bar_y + 6}, {sx + len, bar_y + 6}, kBlack, 2);
    text(header, fmt::format("= {:g} um deflection (x{:.1f})", range_um, magnification),
         {sx + len + 6, bar_y + 11});
  }
}

void draw_plot(cv::Mat& plot, const movie::TactileMovie& movie,
               const std::vector<std::int32_t>& marks) {
  const std::vector<double> rms = frame_rms_um(movie);
  const int left = 56, right = 12, top = 18, bottom = 30;
  const int w = plot.cols - left - right, h = plot.rows - top - bottom;
  if (w < 10 || h < 10) return;
  double peak = 0;
  for (double v : rms) peak = std::max(peak, v);
  const double y_max = peak > 0 ? peak * 1.1 : 1.0;
  const double t_max = std::max(movie.duration_s(), 1e-9);
  const auto px = [&](double t) { return left + static_cast<int>(std::lround(t / t_max * w)); };
  const auto py = [&](double v) { return top + h - static_cast<int>(std::lround(v / y_max * h)); };
  cv::rectangle(plot, {left, top, w, h}, kBlack, 1);
  text(plot, "RMS deflection (um) per frame", {left, top - 5});
  for (int k = 0; k <= 4; ++k) {
    const double v = y_max * k / 4;
    cv::line(plot, {left - 4, py(v)}, {left, py(v)}, kBlack);
    text(plot, fmt::format("{:.1f}", v), {4, py(v) + 4}, 0.35);
    const double t = t_max * k / 4;
    cv::line(plot, {px(t), top + h}, {px(t), top + h + 4}, kBlack);
    text(plot, fmt::format("{:.2f} s", t), {px(t) - 14, top + h + 18}, 0.35);
  }
  for (std::int32_t f : marks) {
    const int x = px(f / movie.rate_hz);
    cv::line(plot, {x, top}, {x, top + h}, kGrey, 1);
  }
  std::vector<cv::Point> line;
  line.reserve(rms.size());
  for (std::size_t f = 0; f < rms.size(); ++f) line.emplace_back(px(f / movie.rate_hz), py(rms[f]));
  if (!line.empty()) cv::polylines(plot, line, false, kPlotBlue, 1, cv::LINE_AA);
}

}  // namespace

void write_preview_strip(const std::filesystem::path& png, const movie::TactileMovie& movie,
                         const PreviewOptions& options) {
  validate_movie(movie);
  if (options.frames < 1 || options.panel_px < 40 || options.plot_height_px < 0) {
    throw std::invalid_argument(fmt::format(
        "preview options: frames {} (need >= 1), panel_px {} (need >= 40), plot_height_px {}",
        options.frames, options.panel_px, options.plot_height_px));
  }
  const double magnification =
      options.magnification > 0 ? options.magnification : movie::auto_magnification(movie);
  const double strain_scale = std::max(movie::movie_strain_full_scale(movie), 1e-6);
  const int width = options.frames * options.panel_px;
  const int strip_y = kPreviewHeaderPx;
  const int label_y = strip_y + options.panel_px;
  const int plot_y = label_y + kPreviewLabelPx;
  cv::Mat img(plot_y + options.plot_height_px, width, CV_8UC3, kWhite);

  cv::Mat header = img(cv::Rect(0, 0, width, kPreviewHeaderPx));
  draw_header(header, movie, magnification, strain_scale, options.panel_px);

  std::vector<std::int32_t> marks;
  const int panels = std::min(options.frames, std::max(movie.frame_count, 0));
  for (int p = 0; p < panels; ++p) {
    const auto f = static_cast<std::int32_t>(
        panels == 1 ? 0
                    : std::lround(static_cast<double>(p) * (movie.frame_count - 1) / (panels - 1)));
    marks.push_back(f);
    cv::Mat panel =
        img(cv::Rect(p * options.panel_px, strip_y, options.panel_px, options.panel_px));
    draw_panel(panel, movie.layout, movie.frame(f), magnification, strain_scale);
    cv::rectangle(img, cv::Rect(p * options.panel_px, strip_y, options.panel_px, options.panel_px),
                  kGrey, 1);
    text(img, fmt::format("t = {:.3f} s", f / movie.rate_hz),
         {p * options.panel_px + 8, label_y + 16});
  }
  if (options.plot_height_px > 0) {
    cv::Mat plot = img(cv::Rect(0, plot_y, width, options.plot_height_px));
    draw_plot(plot, movie, marks);
  }
  write_image_atomically(png, img);
}

}  // namespace tactile::display
