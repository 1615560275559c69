// Charts drawn with cairo (docs/architecture.md, "Dependencies and why"): one drawing function
// per kind, run once on an image surface (PNG) and once on an SVG surface.

#include "tactile/common/chart.hpp"

#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "tactile/common/atomic_write.hpp"

namespace tactile {
namespace {

struct Rgb {
  double r, g, b;
};

// Okabe-Ito, distinguishable with the common colour-vision deficiencies; yellow late because it
// is faint on white.
constexpr Rgb kPalette[] = {{0.000, 0.447, 0.698}, {0.902, 0.624, 0.000}, {0.000, 0.620, 0.451},
                            {0.835, 0.369, 0.000}, {0.800, 0.475, 0.655}, {0.337, 0.706, 0.914},
                            {0.941, 0.894, 0.259}, {0.000, 0.000, 0.000}};
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrey{0.45, 0.45, 0.45};
constexpr Rgb kGrid{0.88, 0.88, 0.88};
constexpr double kTitleSize = 15, kLabelSize = 12, kTickSize = 11, kFooterSize = 9;

Rgb palette(int i) {
  return kPalette[static_cast<std::size_t>(std::max(i, 0)) % std::size(kPalette)];
}

enum class Align { left, centre, right };

// Thin helpers over a cairo context; every chart kind draws with these only.
class Canvas {
 public:
  explicit Canvas(cairo_t* cr) : cr_(cr) {
    cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  }
  void colour(Rgb c, double alpha = 1) { cairo_set_source_rgba(cr_, c.r, c.g, c.b, alpha); }
  double text_width(const std::string& s, double size) {
    cairo_set_font_size(cr_, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr_, s.c_str(), &e);
    return e.x_advance;
  }
  // y is the baseline; angle in degrees, counter-clockwise, about (x, y).
  void text(const std::string& s, double x, double y, double size, Align align = Align::left,
            Rgb c = kBlack, double angle = 0) {
    if (s.empty()) return;
    const double w = text_width(s, size);
    cairo_save(cr_);
    colour(c);
    cairo_translate(cr_, x, y);
    cairo_rotate(cr_, -angle * M_PI / 180);
    cairo_move_to(cr_, align == Align::left ? 0 : align == Align::centre ? -w / 2 : -w, 0);
    cairo_show_text(cr_, s.c_str());
    cairo_restore(cr_);
  }
  void line(double x0, double y0, double x1, double y1, Rgb c, double width = 1,
            bool dashed = false) {
    cairo_save(cr_);
    colour(c);
    cairo_set_line_width(cr_, width);
    if (dashed) {
      const double dash[] = {6, 4};
      cairo_set_dash(cr_, dash, 2, 0);
    }
    cairo_move_to(cr_, x0, y0);
    cairo_line_to(cr_, x1, y1);
    cairo_stroke(cr_);
    cairo_restore(cr_);
  }
  void rect(double x, double y, double w, double h, Rgb fill, Rgb stroke, bool filled = true) {
    cairo_rectangle(cr_, x, y, w, h);
    if (filled) {
      colour(fill);
      cairo_fill_preserve(cr_);
    }
    colour(stroke);
    cairo_set_line_width(cr_, 1);
    cairo_stroke(cr_);
  }
  void fill_rect(double x, double y, double w, double h, Rgb fill) {
    colour(fill);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_fill(cr_);
  }
  void dot(double x, double y, double r, Rgb c, double alpha = 1) {
    colour(c, alpha);
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, x, y, r, 0, 2 * M_PI);
    cairo_fill(cr_);
  }
  void polyline(const std::vector<std::pair<double, double>>& pts, Rgb c, double width) {
    if (pts.empty()) return;
    cairo_save(cr_);
    colour(c);
    cairo_set_line_width(cr_, width);
    cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
    cairo_move_to(cr_, pts[0].first, pts[0].second);
    for (std::size_t i = 1; i < pts.size(); ++i) cairo_line_to(cr_, pts[i].first, pts[i].second);
    cairo_stroke(cr_);
    cairo_restore(cr_);
  }
  void clip(double x, double y, double w, double h) {
    cairo_save(cr_);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_clip(cr_);
  }
  void unclip() { cairo_restore(cr_); }

 private:
  cairo_t* cr_;
};

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

using Drawing = std::function<void(Canvas&)>;

void check(cairo_status_t status, const std::filesystem::path& path) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(
        fmt::format("cannot write {}: {}", path.string(), cairo_status_to_string(status)));
}

// Runs the drawing on a surface; `finish` encodes the surface's bytes.
void render(cairo_surface_t* surface, const Drawing& draw, const std::filesystem::path& path,
            const std::function<cairo_status_t(cairo_surface_t*)>& finish) {
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  Canvas canvas(cr);
  try {
    draw(canvas);
  } catch (...) {
    cairo_destroy(cr);
    throw;
  }
  const cairo_status_t drawn = cairo_status(cr);
  cairo_destroy(cr);
  check(drawn, path);
  check(finish(surface), path);
}

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

ChartFiles write_both(const std::filesystem::path& path, int width, int height,
                      const std::string& title, const std::string& description,
                      const Drawing& draw) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument(
        fmt::format("{}: chart size {} x {}", path.string(), width, height));
  ChartFiles files;
  files.png = std::filesystem::path(path).replace_extension(".png");
  files.svg = std::filesystem::path(path).replace_extension(".svg");

  std::string png;
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  try {
    render(image, draw, files.png,
           [&](cairo_surface_t* s) { return cairo_surface_write_to_png_stream(s, append, &png); });
  } catch (...) {
    cairo_surface_destroy(image);
    throw;
  }
  cairo_surface_destroy(image);

  std::string svg;
  cairo_surface_t* vector = cairo_svg_surface_create_for_stream(append, &svg, width, height);
  try {
    render(vector, draw, files.svg, [](cairo_surface_t* s) {
      cairo_surface_finish(s);
      return cairo_surface_status(s);
    });
  } catch (...) {
    cairo_surface_destroy(vector);
    throw;
  }
  cairo_surface_destroy(vector);
  // cairo names the drawing after a process-wide surface counter; a fixed name makes the same
  // chart the same bytes, however many charts were drawn before it.
  std::string renamed;
  std::size_t from = 0;
  for (std::size_t at = svg.find("surface"); at != std::string::npos;
       at = svg.find("surface", from)) {
    std::size_t digits = at + 7;
    while (digits < svg.size() && std::isdigit(static_cast<unsigned char>(svg[digits]))) ++digits;
    renamed.append(svg, from, at + 7 - from);
    if (digits > at + 7) renamed += '1';
    from = digits;
  }
  renamed.append(svg, from);
  svg = std::move(renamed);
  const std::size_t open = svg.find("<svg");
  const std::size_t end = open == std::string::npos ? open : svg.find('>', open);
  if (end == std::string::npos) throw std::runtime_error("cairo wrote no <svg> element");
  svg.insert(end + 1, fmt::format("\n<title>{}</title>\n<desc>{}</desc>", xml_escaped(title),
                                  xml_escaped(description)));

  write_text_atomically(files.png, png);
  write_text_atomically(files.svg, svg);
  return files;
}

// --- axes -------------------------------------------------------------------------------------

// One axis mapped to pixels: lo..hi (in log10 units on a log axis) onto p0..p1.
struct Scale {
  bool log = false;
  double lo = 0, hi = 1;
  double p0 = 0, p1 = 1;
  double t(double v) const { return log ? std::log10(v) : v; }
  double px(double v) const { return p0 + (t(v) - lo) / (hi - lo) * (p1 - p0); }
  bool valid(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

Scale fit_scale(const ChartAxis& axis, const std::vector<double>& values,
                const std::vector<ChartTarget>& targets) {
  Scale s;
  s.log = axis.scale == AxisScale::log && axis.categories.empty();
  if (!axis.categories.empty()) {
    s.lo = -0.5;
    s.hi = static_cast<double>(axis.categories.size()) - 0.5;
    return s;
  }
  double lo = INFINITY, hi = -INFINITY;
  const auto take = [&](double v) {
    if (!s.valid(v)) return;
    lo = std::min(lo, s.t(v));
    hi = std::max(hi, s.t(v));
  };
  for (double v : values) take(v);
  for (const auto& t : targets) take(t.value);
  if (!(lo <= hi)) lo = 0, hi = 1;  // nothing to fit: an arbitrary unit range
  const double pad = hi > lo ? 0.05 * (hi - lo) : (s.log ? 0.5 : std::max(0.5, 0.1 * std::abs(lo)));
  lo -= pad;
  hi += pad;
  if (s.valid(axis.min)) lo = s.t(axis.min);
  if (s.valid(axis.max)) hi = s.t(axis.max);
  if (!(hi > lo)) hi = lo + 1;
  s.lo = lo;
  s.hi = hi;
  return s;
}

// Linear ticks at multiples of 1, 2 or 5 x 10^k, about five over the range.
std::vector<double> linear_ticks(double lo, double hi) {
  const double raw = (hi - lo) / 5;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 1.5   ? mag
                      : raw / mag < 3.5 ? 2 * mag
                      : raw / mag < 7.5 ? 5 * mag
                                        : 10 * mag;
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; ++k)
    ticks.push_back(std::abs(k) < 1e-9 ? 0.0 : k * step);
  return ticks;
}

// Ticks as (value, label).
std::vector<std::pair<double, std::string>> ticks_of(const Scale& s, const ChartAxis& axis) {
  std::vector<std::pair<double, std::string>> out;
  if (!axis.categories.empty()) {
    for (std::size_t i = 0; i < axis.categories.size(); ++i)
      out.emplace_back(static_cast<double>(i), axis.categories[i]);
    return out;
  }
  if (s.log) {
    // Decades, with 2 and 5 between them when the range holds too few decades to read.
    const int d0 = static_cast<int>(std::floor(s.lo)), d1 = static_cast<int>(std::ceil(s.hi));
    const bool fine = s.hi - s.lo < 2.5;
    for (int d = d0; d <= d1; ++d)
      for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
        const double v = m * std::pow(10.0, d);
        if (std::log10(v) >= s.lo - 1e-9 && std::log10(v) <= s.hi + 1e-9)
          out.emplace_back(v, fmt::format("{:g}", v));
      }
    if (out.size() >= 2) return out;
    out.clear();
    for (double v : linear_ticks(std::pow(10.0, s.lo), std::pow(10.0, s.hi)))
      if (v > 0) out.emplace_back(v, fmt::format("{:g}", v));
    return out;
  }
  for (double v : linear_ticks(s.lo, s.hi)) out.emplace_back(v, fmt::format("{:g}", v));
  return out;
}

void no_data(Canvas& c, double x, double y) {
  c.text("no data", x, y, kTitleSize, Align::centre, kGrey);
}

void footer(Canvas& c, const std::string& text, int height) {
  c.text(text, 10, height - 8, kFooterSize, Align::left, kGrey);
}

std::string count_text(std::size_t drawn, std::size_t left_out, const char* what) {
  return fmt::format("{}{} {} drawn, {} left out (non-finite, or non-positive on a log axis)",
                     drawn == 0 ? "no data: " : "", drawn, what, left_out);
}

enum class Marks { dots, lines };

ChartFiles write_xy(const std::filesystem::path& path, const XYChart& chart, Marks marks) {
  std::vector<double> xs, ys;
  std::size_t drawn = 0, left_out = 0;
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(fmt::format("{}: series '{}' has {} x but {} y", path.string(),
                                              s.label, s.x.size(), s.y.size()));
  }
  const Scale probe_x = fit_scale(chart.x, {}, {}), probe_y = fit_scale(chart.y, {}, {});
  for (const auto& s : chart.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (probe_x.valid(s.x[i]) && probe_y.valid(s.y[i])) {
        xs.push_back(s.x[i]);
        ys.push_back(s.y[i]);
        ++drawn;
      } else {
        ++left_out;
      }
    }
  if (chart.identity_line) {  // the diagonal is only useful if it spans both ranges
    xs.insert(xs.end(), ys.begin(), ys.end());
    ys = xs;
  }

  const auto draw = [&](Canvas& c) {
    double legend_w = 0;
    for (const auto& s : chart.series)
      if (!s.label.empty()) legend_w = std::max(legend_w, c.text_width(s.label, kLabelSize) + 44);
    const double left = 80, top = 46, right = chart.width - 20 - legend_w;
    const double bottom = chart.height - (chart.footer.empty() ? 52 : 68);
    Scale sx = fit_scale(chart.x, xs, chart.x_targets);
    Scale sy = fit_scale(chart.y, ys, chart.y_targets);
    sx.p0 = left, sx.p1 = right, sy.p0 = bottom, sy.p1 = top;

    c.text(chart.title, chart.width / 2.0, 26, kTitleSize, Align::centre);
    for (const auto& [v, label] : ticks_of(sx, chart.x)) {
      const double x = sx.px(v);
      c.line(x, top, x, bottom, kGrid);
      c.line(x, bottom, x, bottom + 5, kBlack);
      c.text(label, x, bottom + 18, kTickSize, Align::centre);
    }
    for (const auto& [v, label] : ticks_of(sy, chart.y)) {
      const double y = sy.px(v);
      c.line(left, y, right, y, kGrid);
      c.line(left - 5, y, left, y, kBlack);
      c.text(label, left - 8, y + 4, kTickSize, Align::right);
    }
    c.rect(left, top, right - left, bottom - top, kBlack, kBlack, false);
    c.text(chart.x.label, (left + right) / 2, bottom + 38, kLabelSize, Align::centre);
    c.text(chart.y.label, 18, (top + bottom) / 2, kLabelSize, Align::centre, kBlack, 90);
    footer(c, chart.footer, chart.height);

    // A little beyond the frame, so that a line along a fixed limit (100 %) shows whole.
    c.clip(left - 3, top - 3, right - left + 6, bottom - top + 6);
    for (const auto& t : chart.x_targets)
      if (sx.valid(t.value)) {
        c.line(sx.px(t.value), top, sx.px(t.value), bottom, kGrey, 1, true);
        c.text(t.label, sx.px(t.value) + 4, top + 14, kTickSize, Align::left, kGrey);
      }
    for (const auto& t : chart.y_targets)
      if (sy.valid(t.value)) {
        c.line(left, sy.px(t.value), right, sy.px(t.value), kGrey, 1, true);
        c.text(t.label, left + 4, sy.px(t.value) - 4, kTickSize, Align::left, kGrey);
      }
    if (chart.identity_line) {
      const double lo =
          std::max(sx.log ? std::pow(10.0, sx.lo) : sx.lo, sy.log ? std::pow(10.0, sy.lo) : sy.lo);
      const double hi =
          std::min(sx.log ? std::pow(10.0, sx.hi) : sx.hi, sy.log ? std::pow(10.0, sy.hi) : sy.hi);
      if (hi > lo) c.line(sx.px(lo), sy.px(lo), sx.px(hi), sy.px(hi), kGrey, 1, true);
    }
    for (std::size_t k = 0; k < chart.series.size(); ++k) {
      const auto& s = chart.series[k];
      const Rgb col = palette(static_cast<int>(k));
      std::vector<std::pair<double, double>> run;
      const auto flush = [&] {
        if (run.size() == 1) c.dot(run[0].first, run[0].second, 2.5, col);
        c.polyline(run, col, s.emphasis ? 3 : 1.5);
        run.clear();
      };
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        const bool ok = sx.valid(s.x[i]) && sy.valid(s.y[i]);
        if (marks == Marks::dots) {
          // Translucent, so that overlapping points show as darker.
          if (ok) c.dot(sx.px(s.x[i]), sy.px(s.y[i]), s.emphasis ? 5.5 : 4, col, 0.7);
        } else if (ok) {
          run.emplace_back(sx.px(s.x[i]), sy.px(s.y[i]));
        } else {
          flush();
        }
      }
      flush();
    }
    c.unclip();
    if (drawn == 0) no_data(c, (left + right) / 2, (top + bottom) / 2);

    double ly = top + 12;
    for (std::size_t k = 0; k < chart.series.size(); ++k) {
      const auto& s = chart.series[k];
      if (s.label.empty()) continue;
      const Rgb col = palette(static_cast<int>(k));
      const double lx = right + 14;
      if (marks == Marks::dots)
        c.dot(lx + 8, ly - 4, s.emphasis ? 5.5 : 4, col);
      else
        c.line(lx, ly - 4, lx + 18, ly - 4, col, s.emphasis ? 3 : 1.5);
      c.text(s.label, lx + 24, ly, kLabelSize);
      ly += 20;
    }
  };
  std::vector<std::string> labels;
  for (const auto& s : chart.series)
    if (!s.label.empty()) labels.push_back(s.label);
  ChartFiles files = write_both(
      path, chart.width, chart.height, chart.title,
      fmt::format("x: {}; y: {}; {}; series: {}", chart.x.label, chart.y.label,
                  count_text(drawn, left_out, marks == Marks::dots ? "points" : "line points"),
                  fmt::join(labels, "; ")),
      draw);
  files.drawn = drawn;
  files.left_out = left_out;
  return files;
}

}  // namespace

void add_point(XYChart& chart, const std::string& label, double x, double y) {
  auto it = std::find_if(chart.series.begin(), chart.series.end(),
                         [&](const ChartSeries& s) { return s.label == label; });
  if (it == chart.series.end()) it = chart.series.insert(chart.series.end(), {.label = label});
  it->x.push_back(x);
  it->y.push_back(y);
}

ChartFiles write_scatter_chart(const std::filesystem::path& path, const XYChart& chart) {
  return write_xy(path, chart, Marks::dots);
}

ChartFiles write_line_chart(const std::filesystem::path& path, const XYChart& chart) {
  return write_xy(path, chart, Marks::lines);
}

ChartFiles write_bar_chart(const std::filesystem::path& path, const BarChart& chart) {
  if (chart.values.size() != chart.labels.size())
    throw std::invalid_argument(fmt::format("{}: {} bar labels but {} values", path.string(),
                                            chart.labels.size(), chart.values.size()));
  const int n = static_cast<int>(chart.values.size());
  const int height = chart.height > 0 ? chart.height : 130 + 22 * n;
  std::size_t drawn = 0;
  for (double v : chart.values) drawn += std::isfinite(v) ? 1 : 0;
  const std::size_t left_out = chart.values.size() - drawn;

  const auto draw = [&](Canvas& c) {
    double label_w = 0;
    for (const auto& l : chart.labels) label_w = std::max(label_w, c.text_width(l, kTickSize));
    const double left = std::min(label_w + 20, chart.width * 0.5), right = chart.width - 60.0;
    const double top = 58, bar_h = 18, gap = 4, bottom = top + n * (bar_h + gap);
    std::vector<double> fit = chart.values;
    fit.push_back(0);  // bars start at zero, so zero is on the axis
    ChartAxis axis{.label = chart.value_label, .min = chart.min, .max = chart.max};
    Scale s = fit_scale(axis, fit, {});
    if (std::isnan(chart.min) && s.lo < 0 && *std::min_element(fit.begin(), fit.end()) >= 0)
      s.lo = 0;  // no margin below zero when nothing is negative
    s.p0 = left, s.p1 = right;
    const auto clamped = [&](double v) { return s.px(std::clamp(v, s.lo, s.hi)); };

    c.text(chart.title, chart.width / 2.0, 26, kTitleSize, Align::centre);
    for (const auto& [v, label] : ticks_of(s, axis)) {
      c.line(s.px(v), top - 5, s.px(v), bottom, kGrid);
      c.text(label, s.px(v), top - 9, kTickSize, Align::centre);
    }
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double y = top + i * (bar_h + gap);
      const double v = chart.values[k];
      c.text(chart.labels[k], left - 8, y + bar_h - 5, kTickSize, Align::right);
      if (!std::isfinite(v)) {
        c.text("n/a", clamped(0) + 4, y + bar_h - 5, kTickSize, Align::left, kGrey);
        continue;
      }
      const double x0 = clamped(0), x1 = clamped(v);
      c.fill_rect(std::min(x0, x1), y, std::max(std::abs(x1 - x0), 1.0), bar_h,
                  palette(k < chart.colours.size() ? chart.colours[k] : 0));
      c.text(fmt::format("{:.3g}", v), std::max(x0, x1) + 4, y + bar_h - 5, kTickSize);
    }
    c.line(clamped(0), top - 2, clamped(0), bottom, kBlack);
    if (n == 0) no_data(c, (left + right) / 2, top + 30);
    c.text(chart.value_label, (left + right) / 2, bottom + 22, kLabelSize, Align::centre);
    double lx = 10;
    for (std::size_t k = 0; k < chart.legend.size(); ++k) {
      c.fill_rect(lx, bottom + 36, 14, 14, palette(static_cast<int>(k)));
      c.text(chart.legend[k], lx + 20, bottom + 48, kLabelSize);
      lx += 34 + c.text_width(chart.legend[k], kLabelSize);
    }
    footer(c, chart.footer, height);
  };
  ChartFiles files =
      write_both(path, chart.width, height, chart.title,
                 fmt::format("value: {}; {}; legend: {}", chart.value_label,
                             count_text(drawn, left_out, "bars"), fmt::join(chart.legend, "; ")),
                 draw);
  files.drawn = drawn;
  files.left_out = left_out;
  return files;
}

ChartFiles write_heatmap(const std::filesystem::path& path, const HeatmapChart& chart) {
  const std::size_t rows = chart.row_names.size(), cols = chart.column_names.size();
  if (chart.values.size() != rows)
    throw std::invalid_argument(
        fmt::format("{}: {} row names but {} rows", path.string(), rows, chart.values.size()));
  for (const auto& r : chart.values)
    if (r.size() != cols)
      throw std::invalid_argument(
          fmt::format("{}: a row of {} values for {} columns", path.string(), r.size(), cols));
  const int width = chart.width > 0 ? chart.width : 200 + 36 * static_cast<int>(cols);
  const int height = chart.height > 0 ? chart.height : 180 + 36 * static_cast<int>(rows);
  std::size_t drawn = 0, left_out = 0;
  for (const auto& r : chart.values)
    for (double v : r) (std::isfinite(v) ? drawn : left_out) += 1;

  const auto draw = [&](Canvas& c) {
    double row_w = 0, col_h = 0;
    for (const auto& s : chart.row_names) row_w = std::max(row_w, c.text_width(s, kTickSize));
    for (const auto& s : chart.column_names) col_h = std::max(col_h, c.text_width(s, kTickSize));
    const double left = 34 + row_w + 8, top = 64 + col_h * 0.87;
    const double cell = std::max(
        4.0, std::min((width - left - 10) / std::max<double>(1, static_cast<double>(cols)),
                      (height - top - 10) / std::max<double>(1, static_cast<double>(rows))));
    c.text(chart.title, width / 2.0, 24, kTitleSize, Align::centre);
    c.text(chart.x_label, left + cell * static_cast<double>(cols) / 2, 44, kLabelSize,
           Align::centre);
    c.text(chart.y_label, 16, top + cell * static_cast<double>(rows) / 2, kLabelSize, Align::centre,
           kBlack, 90);
    for (std::size_t p = 0; p < cols; ++p)
      c.text(chart.column_names[p], left + (static_cast<double>(p) + 0.6) * cell, top - 6,
             kTickSize, Align::left, kBlack, 60);
    for (std::size_t t = 0; t < rows; ++t) {
      double total = 0;
      for (double v : chart.values[t])
        if (std::isfinite(v)) total += v;
      const double y = top + static_cast<double>(t) * cell;
      c.text(chart.row_names[t], left - 6, y + cell * 0.62, kTickSize, Align::right);
      for (std::size_t p = 0; p < cols; ++p) {
        const double v = chart.values[t][p];
        const double share = std::isfinite(v) && total > 0 ? std::clamp(v / total, 0.0, 1.0) : 0;
        const double x = left + static_cast<double>(p) * cell;
        c.rect(x, y, cell, cell, {1 - share, 1 - share, 1}, {0.8, 0.8, 0.8});
        if (std::isfinite(v) && v != 0)
          c.text(fmt::format("{:g}", v), x + cell / 2, y + cell * 0.62, kTickSize, Align::centre,
                 share > 0.5 ? Rgb{1, 1, 1} : kBlack);
      }
    }
    if (drawn == 0) no_data(c, width / 2.0, (top + height) / 2);
  };
  ChartFiles files = write_both(path, width, height, chart.title,
                                fmt::format("columns: {}; rows: {}; {}", chart.x_label,
                                            chart.y_label, count_text(drawn, left_out, "cells")),
                                draw);
  files.drawn = drawn;
  files.left_out = left_out;
  return files;
}

}  // namespace tactile
