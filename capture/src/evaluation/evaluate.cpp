#include "tactile/capture/evaluate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "tactile/common/csv.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {

GroundTruth ground_truth_of(const PrintSequence& seq) {
  GroundTruth truth;
  truth.calibration = seq.calibration;
  truth.landmarks = seq.landmarks;
  truth.warp = seq.spec;
  return truth;
}

int truth_frame_count(const GroundTruth& truth) {
  return truth.warp ? truth.warp->frame_count : truth.spec.frame_count;
}

double truth_rel_change(const GroundTruth& truth, PointMm a_from, PointMm b_from, int frame_from,
                        int frame_to) {
  if (truth.warp) return warp_rel_change(*truth.warp, a_from, b_from, frame_from, frame_to);
  return true_rel_change(truth.spec, a_from, b_from, frame_from, frame_to);
}

namespace {

// The contact map's cells against the warp's contact (Evaluation::contact_cells and after).
void evaluate_contact(const ContactMap& map, const GroundTruth& truth, int frame_count,
                      Evaluation& ev) {
  if (!map.measured() || !truth.warp) return;
  const ContactGrid& g = map.grid;
  const int width = truth.calibration.image_width_px, height = truth.calibration.image_height_px;
  std::int64_t right = 0, both_out = 0, either_out = 0;
  const int frames = std::min(frame_count, map.frame_count());
  for (int f = 0; f < frames; ++f) {
    if (!map.seen(f)) continue;  // dropped by a live session: no claim either way
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.columns; ++c) {
        const int x0 = c * g.cell_px, y0 = r * g.cell_px;
        const int w = std::min(g.cell_px, width - x0), h = std::min(g.cell_px, height - y0);
        double touch = 0;
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) {
            const PointMm at = to_mm(truth.calibration, x0 + (i + 0.5) * w / 4.0 - 0.5,
                                     y0 + (j + 0.5) * h / 4.0 - 0.5);
            touch += warp_contact(*truth.warp, at, f) / 16;
          }
        }
        if (touch > 0.25 && touch < 0.75) continue;  // the rim: half a cell each way
        const bool truth_in = touch >= 0.75;
        const auto i = static_cast<std::size_t>((f * g.rows + r) * g.columns + c);
        const bool map_in = map.in_contact[i] == 1;
        ++ev.contact_cells;
        if (!truth_in) ++ev.gap_cells;
        if (truth_in == map_in) ++right;
        if (!truth_in && !map_in) ++both_out;
        if (!truth_in || !map_in) ++either_out;
      }
    }
  }
  if (ev.contact_cells > 0) {
    ev.contact_agreement = static_cast<double>(right) / static_cast<double>(ev.contact_cells);
    ev.gap_overlap =
        either_out > 0 ? static_cast<double>(both_out) / static_cast<double>(either_out) : 1.0;
  }
}

}  // namespace

Evaluation evaluate_strain(const StrainMovie& movie, const GroundTruth& truth) {
  Evaluation ev;
  const int frame_count = truth_frame_count(truth);
  std::vector<std::vector<const TruthLandmark*>> by_frame(
      static_cast<std::size_t>(std::max(0, frame_count)));
  for (const auto& lm : truth.landmarks) {
    if (lm.frame >= 0 && lm.frame < frame_count) {
      by_frame[static_cast<std::size_t>(lm.frame)].push_back(&lm);
    }
  }
  auto true_mm = [&](const TrackedPoint& p) { return to_mm(truth.calibration, p.x_px, p.y_px); };

  // How much an end of an edge touches the glass, where the scene lifts off.
  ev.has_gap = truth.warp && (truth.warp->contact_loss > 0 || has_contact_patch(*truth.warp));
  const auto contact = [&](const TrackedPoint& p, int frame) {
    return ev.has_gap ? warp_contact(*truth.warp, true_mm(p), frame) : 1.0;
  };
  // Frames where a gap first shows: less than half contact somewhere in the view, nowhere in
  // the frame before (sampled every 2 px, finer than any gap the scenes open); found at the
  // first edge across a gap, as most movies have none.
  std::vector<std::uint8_t> gap_opens;
  const auto gap_opens_at = [&](int frame) {
    if (gap_opens.empty()) {
      gap_opens.assign(static_cast<std::size_t>(std::max(frame_count, 0)), 0);
      bool before = false;
      for (int f = 0; f < frame_count; ++f) {
        const bool now = warp_least_contact(*truth.warp, f, 2) < 0.5;
        gap_opens[static_cast<std::size_t>(f)] = now && !before && f > 0 ? 1 : 0;
        before = now;
      }
    }
    return gap_opens[static_cast<std::size_t>(frame)] != 0;
  };
  double se_contact = 0;
  std::vector<double> measured_contact, truth_contact;

  double se_all = 0, st_all = 0;
  std::vector<double> measured_all, truth_all;  // every compared edge, for the correlation
  std::vector<double> tracked, yields;
  for (const auto& f : movie.frames) {
    FrameEvaluation fe;
    fe.frame_from = f.frame_from;
    fe.frame_to = f.frame_to;
    fe.tracked_points = static_cast<std::int32_t>(f.points_from.size());
    if (f.frame_from >= 0 && f.frame_from < frame_count && f.frame_to < frame_count) {
      fe.truth_landmarks =
          static_cast<std::int32_t>(by_frame[static_cast<std::size_t>(f.frame_from)].size());
      std::unordered_map<std::int32_t, std::size_t> index;
      for (std::size_t i = 0; i < f.points_from.size(); ++i) index[f.points_from[i].track_id] = i;
      double se = 0, st = 0;
      for (const auto& e : f.edges) {
        const auto a = index.find(e.track_a);
        const auto b = index.find(e.track_b);
        if (a == index.end() || b == index.end()) continue;
        const double t =
            truth_rel_change(truth, true_mm(f.points_from[a->second]),
                             true_mm(f.points_from[b->second]), f.frame_from, f.frame_to);
        se += (e.rel_change - t) * (e.rel_change - t);
        measured_all.push_back(e.rel_change);
        truth_all.push_back(t);
        st += t * t;
        ++fe.edges;
        if (ev.has_gap) {
          const double least_from = std::min(contact(f.points_from[a->second], f.frame_from),
                                             contact(f.points_from[b->second], f.frame_from));
          const double least_to = std::min(contact(f.points_to[a->second], f.frame_to),
                                           contact(f.points_to[b->second], f.frame_to));
          const double least = std::min(least_from, least_to);
          if (least < 0.5) {
            ++ev.edges_across_gap;
            // Every end below half contact is in a frame where the gap opens.
            if ((least_from >= 0.5 || gap_opens_at(f.frame_from)) &&
                (least_to >= 0.5 || gap_opens_at(f.frame_to))) {
              ++ev.edges_across_gap_opening;
            }
          }
          if (least >= 1.0) {
            ++fe.edges_in_contact;
            fe.rms_error_in_contact += (e.rel_change - t) * (e.rel_change - t);
            se_contact += (e.rel_change - t) * (e.rel_change - t);
            measured_contact.push_back(e.rel_change);
            truth_contact.push_back(t);
          }
        }
      }
      if (fe.edges_in_contact > 0) {
        fe.rms_error_in_contact = std::sqrt(fe.rms_error_in_contact / fe.edges_in_contact);
      }
      if (fe.edges > 0) {
        fe.rms_error = std::sqrt(se / fe.edges);
        fe.rms_truth = std::sqrt(st / fe.edges);
      }
      se_all += se;
      st_all += st;
      ev.edges += fe.edges;
    }
    tracked.push_back(fe.tracked_points);
    if (fe.truth_landmarks > 0) yields.push_back(double(fe.tracked_points) / fe.truth_landmarks);
    ev.frames.push_back(fe);
  }
  if (ev.edges > 0) {
    ev.rms_error = std::sqrt(se_all / static_cast<double>(ev.edges));
    ev.rms_truth = std::sqrt(st_all / static_cast<double>(ev.edges));
    // A truth without strain (rigid motion) varies by rounding only: no correlation to report.
    ev.correlation = pearson(measured_all, truth_all, 1e-18);
  }
  ev.edges_in_contact = static_cast<std::int64_t>(measured_contact.size());
  if (ev.edges_in_contact > 0) {
    ev.rms_error_in_contact = std::sqrt(se_contact / static_cast<double>(ev.edges_in_contact));
    ev.correlation_in_contact = pearson(measured_contact, truth_contact, 1e-18);
  }
  ev.median_tracked_points = median(tracked);
  ev.median_yield = median(yields);
  if (ev.has_gap) evaluate_contact(movie.contact, truth, frame_count, ev);

  // Localisation of every tracked point against the landmarks of its frame.
  double sd = 0;
  std::map<std::int32_t, int> lengths;
  for (const auto& p : movie.tracks) {
    ++lengths[p.track_id];
    if (p.frame < 0 || p.frame >= frame_count) {
      ++ev.unmatched_points;
      continue;
    }
    const PointMm mm = true_mm(p);
    double best = ev.match_bound_mm;
    bool found = false;
    for (const TruthLandmark* lm : by_frame[static_cast<std::size_t>(p.frame)]) {
      const double dx = lm->x_mm - mm.x_mm, dy = lm->y_mm - mm.y_mm;
      // Nearly every landmark of a frame lies far from the point: the squared distance, within a
      // few units in the last place of the distance's square, rules it out without the exact
      // (and slow) hypot, so the nearest is the same to the bit.
      if (dx * dx + dy * dy > best * best * (1 + 1e-9)) continue;
      const double d = std::hypot(dx, dy);
      if (d <= best) {
        best = d;
        found = true;
      }
    }
    if (found) {
      sd += best * best;
      ++ev.located_points;
    } else {
      ++ev.unmatched_points;
    }
  }
  if (ev.located_points > 0) {
    ev.localisation_rms_mm = std::sqrt(sd / static_cast<double>(ev.located_points));
  }
  std::vector<double> len;
  for (const auto& [id, n] : lengths) len.push_back(n);
  ev.track_count = static_cast<std::int32_t>(len.size());
  ev.median_track_frames = median(len);
  double total = 0;
  for (double l : len) total += l;
  ev.mean_track_frames = len.empty() ? 0.0 : total / static_cast<double>(len.size());
  return ev;
}

void write_evaluation_csv(const std::filesystem::path& dir, const Evaluation& ev) {
  std::filesystem::create_directories(dir);
  const auto frames_path = dir / "evaluation_frames.csv";
  auto out = csv::open_with_header(
      frames_path, "frame_from,frame_to,edges,rms_error,rms_truth,tracked_points,truth_landmarks");
  for (const auto& f : ev.frames) {
    out << fmt::format("{},{},{},{:.6g},{:.6g},{},{}\n", f.frame_from, f.frame_to, f.edges,
                       f.rms_error, f.rms_truth, f.tracked_points, f.truth_landmarks);
  }
  csv::finish(out, frames_path);
  const auto summary_path = dir / "evaluation_summary.csv";
  auto s = csv::open_with_header(summary_path, "metric,value");
  s << fmt::format("edges,{}\n", ev.edges) << fmt::format("rms_error,{:.6g}\n", ev.rms_error)
    << fmt::format("rms_truth,{:.6g}\n", ev.rms_truth)
    << fmt::format("correlation,{:.6g}\n", ev.correlation)
    << fmt::format("localisation_rms_mm,{:.6g}\n", ev.localisation_rms_mm)
    << fmt::format("located_points,{}\n", ev.located_points)
    << fmt::format("unmatched_points,{}\n", ev.unmatched_points)
    << fmt::format("median_tracked_points,{:.6g}\n", ev.median_tracked_points)
    << fmt::format("median_yield,{:.6g}\n", ev.median_yield)
    << fmt::format("track_count,{}\n", ev.track_count)
    << fmt::format("median_track_frames,{:.6g}\n", ev.median_track_frames)
    << fmt::format("mean_track_frames,{:.6g}\n", ev.mean_track_frames);
  if (ev.has_gap) {
    s << fmt::format("edges_in_contact,{}\n", ev.edges_in_contact)
      << fmt::format("rms_error_in_contact,{:.6g}\n", ev.rms_error_in_contact)
      << fmt::format("correlation_in_contact,{:.6g}\n", ev.correlation_in_contact)
      << fmt::format("edges_across_gap,{}\n", ev.edges_across_gap)
      << fmt::format("edges_across_gap_opening,{}\n", ev.edges_across_gap_opening);
  }
  if (ev.contact_cells > 0) {
    s << fmt::format("contact_cells,{}\n", ev.contact_cells)
      << fmt::format("gap_cells,{}\n", ev.gap_cells)
      << fmt::format("contact_agreement,{:.6g}\n", ev.contact_agreement)
      << fmt::format("gap_overlap,{:.6g}\n", ev.gap_overlap);
  }
  csv::finish(s, summary_path);
}

}  // namespace tactile::capture
