// Table 2 and Figure 7 files (see report.hpp); the charts are drawn by common's chart module.

#include "tactile/perception/report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/parallel_for.hpp"

namespace tactile::perception {
namespace {
constexpr const char* kCurvatureNames[3] = {"planar", "conical", "spherical"};
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

ChartFiles write_figure7_chart(const std::filesystem::path& path, const CascadeResult& r) {
  constexpr double kRange = 25;  // mm, both axes: the largest footprint and some room
  XYChart chart{.title = fmt::format(
                    "Predicted vs true signed footprint ({} inputs, exponent {}): {}/{} curvature "
                    "correct",
                    r.inputs, r.degree, r.correct, r.tested),
                .x = {.label = "true footprint (mm, + bump, - pit)", .min = -kRange, .max = kRange},
                .y = {.label = "predicted footprint (mm)", .min = -kRange, .max = kRange},
                .identity_line = true,
                .width = 800,
                .height = 600};
  for (int c = 0; c < 3; ++c)
    chart.series.push_back({.label = fmt::format("{}: R2 {:.3f}, RMS {:.2f} mm", kCurvatureNames[c],
                                                 r.r2[c], r.rms_mm[c])});
  // A wild prediction is drawn at the edge rather than dropped, so that every trial is seen.
  for (const auto& p : r.predictions) {
    auto& s = chart.series[static_cast<std::size_t>(p.curvature)];
    s.x.push_back(p.true_mm);
    s.y.push_back(std::clamp(p.predicted_mm, -kRange, kRange));
  }
  return write_scatter_chart(path, chart);
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

ChartFiles write_accuracy_by_footprint_chart(const std::filesystem::path& path,
                                             const std::vector<TimedCascade>& rows, int degree) {
  // Footprints span 1.25 to 20 mm, so the axis is ordinal (one slot per footprint in the data),
  // not linear: the small features, where the classifier fails, would otherwise share a pixel.
  std::vector<double> footprints;
  for (const auto& row : rows)
    if (row.result.degree == degree)
      for (const auto& a : accuracy_by_footprint(row.result))
        if (std::find(footprints.begin(), footprints.end(), a.footprint_mm) == footprints.end())
          footprints.push_back(a.footprint_mm);
  std::sort(footprints.begin(), footprints.end());
  XYChart chart{.title = fmt::format(
                    "Held-out curvature accuracy per footprint (kernel exponent {})", degree),
                .x = {.label = "true signed footprint (mm, + bump, - pit)"},
                .y = {.label = "curvature correct (%)", .min = 0, .max = 100},
                .y_targets = {{.value = 100.0 / 3, .label = "chance"}},
                .width = 900,
                .height = 460};
  for (double mm : footprints) chart.x.categories.push_back(fmt::format("{:+g}", mm));
  for (const auto& row : rows) {
    const CascadeResult& r = row.result;
    if (r.degree != degree) continue;
    ChartSeries s{.label = fmt::format("{} ({}/{})", r.inputs, r.correct, r.tested),
                  .emphasis = r.inputs == "all"};
    for (const auto& a : accuracy_by_footprint(r)) {
      s.x.push_back(static_cast<double>(
          std::find(footprints.begin(), footprints.end(), a.footprint_mm) - footprints.begin()));
      s.y.push_back(a.tested ? 100.0 * a.correct / a.tested : 0.0);
    }
    chart.series.push_back(std::move(s));
  }
  return write_line_chart(path, chart);
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

ChartFiles write_confusion_chart(const std::filesystem::path& path,
                                 const std::vector<std::string>& class_names,
                                 const std::vector<std::vector<int>>& confusion) {
  HeatmapChart chart{.title = "Confusion matrix",
                     .x_label = "predicted class",
                     .y_label = "true class",
                     .row_names = class_names,
                     .column_names = class_names};
  for (const auto& row : confusion) chart.values.emplace_back(row.begin(), row.end());
  return write_heatmap(path, chart);
}

std::vector<std::size_t> confusion_order(const std::vector<std::vector<int>>& confusion) {
  const std::size_t n = confusion.size();
  const auto link = [&](std::size_t a, std::size_t b) {
    return a == b ? 0 : confusion.at(a).at(b) + confusion.at(b).at(a);
  };
  std::vector<bool> placed(n, false);
  std::vector<std::size_t> order;
  std::deque<std::size_t> chain;
  const auto close_chain = [&] {
    order.insert(order.end(), chain.begin(), chain.end());
    chain.clear();
  };
  while (true) {
    // The unplaced class most confused with an end of the chain (or, with no chain, the most
    // confused unplaced pair); the first in index order on ties.
    int best = 0;
    std::size_t best_k = n, best_end = n;
    if (chain.empty()) {
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b)
          if (!placed[a] && !placed[b] && link(a, b) > best) {
            best = link(a, b);
            best_k = b;
            best_end = a;
          }
      if (best == 0) break;
      chain.push_back(best_end);
      placed[best_end] = true;
      chain.push_back(best_k);
      placed[best_k] = true;
      continue;
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (placed[k]) continue;
      for (const std::size_t end : {chain.front(), chain.back()})
        if (link(k, end) > best) {
          best = link(k, end);
          best_k = k;
          best_end = end;
        }
    }
    if (best == 0) {
      close_chain();
      continue;
    }
    if (best_end == chain.front() && best_end != chain.back())
      chain.push_front(best_k);
    else
      chain.push_back(best_k);
    placed[best_k] = true;
  }
  close_chain();
  for (std::size_t k = 0; k < n; ++k)
    if (!placed[k]) order.push_back(k);
  return order;
}

void write_confusion_report(const std::filesystem::path& dir,
                            const std::vector<std::string>& class_names,
                            const std::vector<std::vector<int>>& confusion) {
  const auto order = confusion_order(confusion);
  std::vector<std::string> names;
  std::vector<std::vector<int>> ordered;
  for (const auto r : order) {
    names.push_back(class_names.at(r));
    auto& row = ordered.emplace_back();
    for (const auto c : order) row.push_back(confusion.at(r).at(c));
  }
  std::filesystem::create_directories(dir);
  const auto path = dir / "confusion.csv";
  auto out = csv::open_with_header(path, fmt::format("true\\predicted,{}", fmt::join(names, ",")));
  for (std::size_t r = 0; r < ordered.size(); ++r)
    out << names[r] << ',' << fmt::format("{}", fmt::join(ordered[r], ",")) << '\n';
  csv::finish(out, path);
  write_confusion_chart(dir / "confusion.svg", names, ordered);
}

void write_predictions_csv(const std::filesystem::path& path,
                           const std::vector<std::string>& class_names, const LabelledInputs& data,
                           const ClassifierTest& test, bool with_values) {
  auto out =
      csv::open_with_header(path, with_values ? "file,class,predicted,correct,value,predicted_value"
                                              : "file,class,predicted,correct");
  for (std::size_t i = 0; i < data.rows.size(); ++i) {
    const auto& p = test.predictions.at(i);
    out << fmt::format("{},{},{},{}", data.files[i],
                       class_names.at(static_cast<std::size_t>(data.classes[i])),
                       class_names.at(static_cast<std::size_t>(p.class_index)),
                       p.class_index == data.classes[i] ? 1 : 0);
    if (with_values) out << fmt::format(",{:g},{:.6g}", data.values.at(i), p.value);
    out << '\n';
  }
  csv::finish(out, path);
}

std::vector<std::string> confusion_lines(const std::vector<std::string>& class_names,
                                         const std::vector<std::vector<int>>& confusion) {
  std::vector<std::string> lines;
  for (std::size_t c = 0; c < class_names.size(); ++c) {
    int total = 0;
    std::vector<std::string> wrong;
    for (std::size_t p = 0; p < class_names.size(); ++p) {
      total += confusion.at(c).at(p);
      if (p != c && confusion[c][p])
        wrong.push_back(fmt::format("{} {}", class_names[p], confusion[c][p]));
    }
    if (total == 0) continue;
    lines.push_back(fmt::format("{}: {}/{} correct{}{}", class_names[c], confusion[c][c], total,
                                wrong.empty() ? "" : "; taken for ", fmt::join(wrong, ", ")));
  }
  return lines;
}

void write_test_report(const std::filesystem::path& dir,
                       const std::vector<std::string>& class_names, const LabelledInputs& data,
                       const ClassifierTest& test, bool with_values) {
  CommitTogether together;
  write_confusion_report(dir, class_names, test.confusion);
  write_predictions_csv(dir / "predictions.csv", class_names, data, test, with_values);
  together.commit();
}

}  // namespace tactile::perception
