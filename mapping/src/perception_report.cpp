// Table 2 and Figure 7 files (see perception_report.hpp).

#include "tactile/mapping/perception_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>

#include "parallel_for.hpp"
#include "tactile/common/csv.hpp"

namespace tactile::mapping {
namespace {
constexpr const char* kCurvatureNames[3] = {"planar", "conical", "spherical"};
constexpr const char* kColours[3] = {"#1f77b4", "#d62728", "#2ca02c"};
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
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  out << fmt::format(
      "<svg xmlns='http://www.w3.org/2000/svg' width='{0}' height='{1}' "
      "font-family='sans-serif' font-size='13'>\n<rect width='100%' height='100%' fill='white'/>\n",
      kSize + 2 * kMargin, kSize + 2 * kMargin + 20);
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
  out << "</svg>\n";
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("writing {} failed", path.string()));
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

}  // namespace tactile::mapping
