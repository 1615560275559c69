// Table 2 and Figure 7 files (see perception_report.hpp).

#include "tactile/perception/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "tactile/common/csv.hpp"
#include "tactile/common/parallel_for.hpp"

namespace tactile::perception {
namespace {
constexpr const char* kCurvatureNames[3] = {"planar", "conical", "spherical"};
constexpr const char* kColours[3] = {"#1f77b4", "#d62728", "#2ca02c"};

std::ofstream open_svg(const std::filesystem::path& path, double width, double height) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  out << fmt::format(
      "<svg xmlns='http://www.w3.org/2000/svg' width='{0}' height='{1}' "
      "font-family='sans-serif' font-size='13'>\n<rect width='100%' height='100%' fill='white'/>\n",
      width, height);
  return out;
}

void finish_svg(std::ofstream& out, const std::filesystem::path& path) {
  out << "</svg>\n";
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("writing {} failed", path.string()));
}
}  // namespace

std::vector<TimedCascade> run_table2(const PerceptionDataset& d, const PerceptionSplit& split,
                                     const std::vector<int>& degrees) {
  struct Job {
    InputSet inputs;
    int degree;
  };
  std::vector<Job> jobs;
  for (const auto& inputs : table2_input_sets(d))
    for (int degree : degrees) jobs.push_back({inputs, degree});
  // The rows are independent models on read-only data, so they run on every core; each row's
  // time is its own training and testing, as a single-threaded run would measure it.
  std::vector<TimedCascade> rows(jobs.size());
  parallel_for(jobs.size(), worker_count(0), [&](std::size_t i) {
    const auto t0 = std::chrono::steady_clock::now();
    CascadeResult r = evaluate_cascade(d, split, jobs[i].inputs, jobs[i].degree);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rows[i] = {std::move(r), s};
  });
  return rows;
}

void write_table2_csv(const std::filesystem::path& path, const std::vector<TimedCascade>& rows) {
  std::string header = "inputs,degree,correct,tested,accuracy";
  for (int t = 0; t < 3; ++t)
    for (int p = 0; p < 3; ++p) header += fmt::format(",true_{}_as_{}", t, p);
  for (const char* c : kCurvatureNames) header += fmt::format(",r2_{}", c);
  for (const char* c : kCurvatureNames) header += fmt::format(",rms_{}_mm", c);
  header += ",cascade_rms_mm,train_test_s";
  auto out = csv::open_with_header(path, header);
  for (const auto& row : rows) {
    const auto& r = row.result;
    out << fmt::format("{},{},{},{},{:.4f}", r.inputs, r.degree, r.correct, r.tested,
                       r.tested ? double(r.correct) / r.tested : 0.0);
    for (const auto& line : r.confusion)
      for (int v : line) out << ',' << v;
    for (double v : r.r2) out << fmt::format(",{:.4f}", v);
    for (double v : r.rms_mm) out << fmt::format(",{:.4f}", v);
    out << fmt::format(",{:.4f},{:.4f}\n", r.cascade_rms_mm, row.train_test_s);
  }
  csv::finish(out, path);
}

void write_figure7_csv(const std::filesystem::path& path, const std::vector<TimedCascade>& rows) {
  auto out = csv::open_with_header(
      path, "inputs,degree,curvature,predicted_curvature,true_footprint_mm,predicted_footprint_mm");
  for (const auto& row : rows)
    for (const auto& p : row.result.predictions)
      out << fmt::format("{},{},{},{},{:g},{:.4f}\n", row.result.inputs, row.result.degree,
                         kCurvatureNames[p.curvature], kCurvatureNames[p.predicted_curvature],
                         p.true_mm, p.predicted_mm);
  csv::finish(out, path);
}

void write_figure7_svg(const std::filesystem::path& path, const CascadeResult& r) {
  // Square plot, both axes -25..25 mm, identity line dashed.
  constexpr double kSize = 480, kMargin = 60, kRange = 25;
  const auto px = [&](double mm) { return kMargin + (mm + kRange) / (2 * kRange) * kSize; };
  const auto py = [&](double mm) { return kMargin + (kRange - mm) / (2 * kRange) * kSize; };
  std::ofstream out = open_svg(path, kSize + 2 * kMargin, kSize + 2 * kMargin + 20);
  out << fmt::format(
      "<text x='{}' y='25' text-anchor='middle' font-size='15'>Predicted vs true signed "
      "footprint ({} inputs, exponent {}): {}/{} curvature correct</text>\n",
      kMargin + kSize / 2, r.inputs, r.degree, r.correct, r.tested);
  out << fmt::format("<rect x='{}' y='{}' width='{}' height='{}' fill='none' stroke='black'/>\n",
                     kMargin, kMargin, kSize, kSize);
  for (int mm = -20; mm <= 20; mm += 5) {
    out << fmt::format("<text x='{}' y='{}' text-anchor='middle'>{}</text>\n", px(mm),
                       kMargin + kSize + 16, mm);
    out << fmt::format("<text x='{}' y='{}' text-anchor='end'>{}</text>\n", kMargin - 6, py(mm) + 4,
                       mm);
  }
  out << fmt::format(
      "<line x1='{}' y1='{}' x2='{}' y2='{}' stroke='grey' stroke-dasharray='4 4'/>\n", px(-kRange),
      py(-kRange), px(kRange), py(kRange));
  out << fmt::format(
      "<text x='{}' y='{}' text-anchor='middle'>true footprint (mm, + bump, - "
      "pit)</text>\n",
      kMargin + kSize / 2, kMargin + kSize + 36);
  out << fmt::format(
      "<text transform='translate(18 {}) rotate(-90)' text-anchor='middle'>predicted footprint "
      "(mm)</text>\n",
      kMargin + kSize / 2);
  for (const auto& p : r.predictions)
    out << fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='3.5' fill='{}' fill-opacity='0.6'/>\n",
                       px(p.true_mm), py(std::clamp(p.predicted_mm, -kRange, kRange)),
                       kColours[p.curvature]);
  for (int c = 0; c < 3; ++c)
    out << fmt::format(
        "<circle cx='{0}' cy='{1}' r='5' fill='{2}'/><text x='{3}' y='{4}'>{5}: R2 {6:.3f}, RMS "
        "{7:.2f} mm</text>\n",
        kMargin + 15, kMargin + 15 + 20 * c, kColours[c], kMargin + 26, kMargin + 20 + 20 * c,
        kCurvatureNames[c], r.r2[c], r.rms_mm[c]);
  finish_svg(out, path);
}

std::vector<FootprintAccuracy> accuracy_by_footprint(const CascadeResult& result) {
  std::vector<FootprintAccuracy> out;
  for (const auto& p : result.predictions) {
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const FootprintAccuracy& a) { return a.footprint_mm == p.true_mm; });
    if (it == out.end()) it = out.insert(out.end(), FootprintAccuracy{p.true_mm, 0, 0});
    ++it->tested;
    if (p.predicted_curvature == p.curvature) ++it->correct;
  }
  std::sort(out.begin(), out.end(), [](const FootprintAccuracy& a, const FootprintAccuracy& b) {
    return a.footprint_mm < b.footprint_mm;
  });
  return out;
}

void write_accuracy_by_footprint_csv(const std::filesystem::path& path,
                                     const std::vector<TimedCascade>& rows) {
  auto out = csv::open_with_header(path, "inputs,degree,footprint_mm,correct,tested,accuracy");
  for (const auto& row : rows)
    for (const auto& a : accuracy_by_footprint(row.result))
      out << fmt::format("{},{},{:g},{},{},{:.4f}\n", row.result.inputs, row.result.degree,
                         a.footprint_mm, a.correct, a.tested,
                         a.tested ? double(a.correct) / a.tested : 0.0);
  csv::finish(out, path);
}

void write_accuracy_by_footprint_svg(const std::filesystem::path& path,
                                     const std::vector<TimedCascade>& rows, int degree) {
  constexpr const char* kSetColours[] = {"#000000", "#ff7f0e", "#1f77b4", "#2ca02c",
                                         "#9467bd", "#8c564b", "#e377c2"};
  // Footprints span 1.25 to 20 mm, so the axis is ordinal (one slot per footprint in the data),
  // not linear: the small features, where the classifier fails, would otherwise share a pixel.
  struct Line {
    const CascadeResult* result;
    std::vector<FootprintAccuracy> points;
  };
  std::vector<Line> lines;
  std::vector<double> footprints;
  for (const auto& row : rows) {
    if (row.result.degree != degree) continue;
    lines.push_back({&row.result, accuracy_by_footprint(row.result)});
    for (const auto& a : lines.back().points)
      if (std::find(footprints.begin(), footprints.end(), a.footprint_mm) == footprints.end())
        footprints.push_back(a.footprint_mm);
  }
  std::sort(footprints.begin(), footprints.end());
  constexpr double kWidth = 640, kHeight = 320, kMargin = 60;
  const double slot = kWidth / std::max<std::size_t>(1, footprints.size());
  const auto px = [&](double mm) {
    const auto i = std::find(footprints.begin(), footprints.end(), mm) - footprints.begin();
    return kMargin + (static_cast<double>(i) + 0.5) * slot;
  };
  const auto py = [&](double fraction) { return kMargin + (1 - fraction) * kHeight; };
  std::ofstream out = open_svg(path, kWidth + 2 * kMargin + 120, kHeight + 2 * kMargin + 20);
  out << fmt::format(
      "<text x='{}' y='25' text-anchor='middle' font-size='15'>Held-out curvature accuracy per "
      "footprint (kernel exponent {})</text>\n",
      kMargin + kWidth / 2, degree);
  out << fmt::format("<rect x='{}' y='{}' width='{}' height='{}' fill='none' stroke='black'/>\n",
                     kMargin, kMargin, kWidth, kHeight);
  for (int pct = 0; pct <= 100; pct += 25)
    out << fmt::format(
        "<line x1='{0}' y1='{1}' x2='{2}' y2='{1}' stroke='#dddddd'/><text x='{3}' y='{4}' "
        "text-anchor='end'>{5} %</text>\n",
        kMargin, py(pct / 100.0), kMargin + kWidth, kMargin - 6, py(pct / 100.0) + 4, pct);
  out << fmt::format(
      "<line x1='{0}' y1='{1:.1f}' x2='{2}' y2='{1:.1f}' stroke='grey' stroke-dasharray='4 4'/>"
      "<text x='{3}' y='{4:.1f}' fill='grey' font-size='11'>chance</text>\n",
      kMargin, py(1.0 / 3), kMargin + kWidth, kMargin + 4, py(1.0 / 3) - 4);
  for (double mm : footprints)
    out << fmt::format("<text x='{}' y='{}' text-anchor='middle' font-size='11'>{:+g}</text>\n",
                       px(mm), kMargin + kHeight + 16, mm);
  out << fmt::format(
      "<text x='{}' y='{}' text-anchor='middle'>true signed footprint (mm, + bump, - pit)"
      "</text>\n",
      kMargin + kWidth / 2, kMargin + kHeight + 40);
  for (std::size_t set = 0; set < lines.size(); ++set) {
    const CascadeResult& r = *lines[set].result;
    const char* colour = kSetColours[set % std::size(kSetColours)];
    std::string points;
    for (const auto& a : lines[set].points)
      points += fmt::format("{:.1f},{:.1f} ", px(a.footprint_mm),
                            py(a.tested ? double(a.correct) / a.tested : 0.0));
    out << fmt::format(
        "<polyline points='{}' fill='none' stroke='{}' stroke-width='{}'/>\n<text x='{}' "
        "y='{}' fill='{}'>{} ({}/{})</text>\n",
        points, colour, r.inputs == "all" ? 2.5 : 1.2, kMargin + kWidth + 10,
        kMargin + 14 + 18 * static_cast<double>(set), colour, r.inputs, r.correct, r.tested);
  }
  finish_svg(out, path);
}

std::string table2_line(const TimedCascade& row) {
  const auto& r = row.result;
  return fmt::format(
      "{:<7} exp {}  {:>3}/{:<3} ({:5.1f} %)  R2 {:.3f} {:.3f} {:.3f}  RMS {:.2f} {:.2f} {:.2f} mm "
      " "
      "cascade RMS {:.2f} mm  {:.3f} s",
      r.inputs, r.degree, r.correct, r.tested, r.tested ? 100.0 * r.correct / r.tested : 0.0,
      r.r2[0], r.r2[1], r.r2[2], r.rms_mm[0], r.rms_mm[1], r.rms_mm[2], r.cascade_rms_mm,
      row.train_test_s);
}

std::string misclassified_line(const CascadeResult& result) {
  std::vector<FootprintAccuracy> by_size;  // footprint_mm unsigned here
  for (const auto& a : accuracy_by_footprint(result)) {
    const double size_mm = std::abs(a.footprint_mm);
    auto it = std::find_if(by_size.begin(), by_size.end(),
                           [&](const FootprintAccuracy& b) { return b.footprint_mm == size_mm; });
    if (it == by_size.end()) it = by_size.insert(by_size.end(), FootprintAccuracy{size_mm, 0, 0});
    it->correct += a.correct;
    it->tested += a.tested;
  }
  std::erase_if(by_size, [](const FootprintAccuracy& a) { return a.correct == a.tested; });
  // Largest share wrong first; equal shares by size.
  std::sort(by_size.begin(), by_size.end(),
            [](const FootprintAccuracy& a, const FootprintAccuracy& b) {
              const double wrong_a = double(a.tested - a.correct) / a.tested;
              const double wrong_b = double(b.tested - b.correct) / b.tested;
              return wrong_a != wrong_b ? wrong_a > wrong_b : a.footprint_mm < b.footprint_mm;
            });
  std::string line = fmt::format("{} exp {}: curvature wrong on {} of {}", result.inputs,
                                 result.degree, result.tested - result.correct, result.tested);
  for (std::size_t i = 0; i < by_size.size(); ++i)
    line += fmt::format("{}{:g} mm {} of {}", i == 0 ? ": " : ", ", by_size[i].footprint_mm,
                        by_size[i].tested - by_size[i].correct, by_size[i].tested);
  return line;
}

void write_confusion_svg(const std::filesystem::path& path,
                         const std::vector<std::string>& class_names,
                         const std::vector<std::vector<int>>& confusion) {
  constexpr double kCell = 28, kLabel = 90;
  const double n = static_cast<double>(class_names.size());
  std::ofstream out = open_svg(path, kLabel + n * kCell + 20, kLabel + n * kCell + 40);
  out << fmt::format(
      "<text x='{}' y='16' text-anchor='middle'>predicted class (columns) against true class "
      "(rows)</text>\n",
      (kLabel + n * kCell + 20) / 2);
  for (std::size_t t = 0; t < class_names.size(); ++t) {
    int total = 0;
    for (int v : confusion.at(t)) total += v;
    const double y = kLabel + static_cast<double>(t) * kCell;
    out << fmt::format("<text x='{}' y='{}' text-anchor='end'>{}</text>\n", kLabel - 4,
                       y + kCell * 0.65, class_names[t]);
    out << fmt::format("<text transform='translate({},{}) rotate(-60)' font-size='11'>{}</text>\n",
                       kLabel + static_cast<double>(t) * kCell + kCell * 0.6, kLabel - 4,
                       class_names[t]);
    for (std::size_t p = 0; p < class_names.size(); ++p) {
      const int v = confusion.at(t).at(p);
      const double share = total ? static_cast<double>(v) / total : 0.0;
      const int shade = static_cast<int>(std::lround(255 * (1 - share)));
      const double x = kLabel + static_cast<double>(p) * kCell;
      out << fmt::format(
          "<rect x='{}' y='{}' width='{}' height='{}' fill='rgb({},{},255)' stroke='#ccc'/>\n", x,
          y, kCell, kCell, shade, shade);
      if (v)
        out << fmt::format("<text x='{}' y='{}' text-anchor='middle' fill='{}'>{}</text>\n",
                           x + kCell / 2, y + kCell * 0.65, share > 0.5 ? "white" : "black", v);
    }
  }
  finish_svg(out, path);
}

}  // namespace tactile::perception
