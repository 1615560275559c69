#include "landmarks/skeleton_repair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "landmarks/thinning.hpp"

namespace tactile::capture {

namespace {

// Ring of 8 neighbours, 4-neighbours first so that walks go round a staircase's corner pixels
// instead of cutting them (a cut corner would survive the removal of its segment).
constexpr int kSteps[8][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};

struct Node {
  std::vector<cv::Point> pixels;
  cv::Point2d centre;
  bool ending = false;  // else a fork
  std::vector<int> segments;
};

// A path between two nodes; `path` runs from a pixel of node a to a pixel of node b.
struct Segment {
  int a = -1;
  int b = -1;
  std::vector<cv::Point> path;  // includes the two node pixels at its ends
  std::vector<cv::Point> interior;
  double length_px = 0;
};

struct Graph {
  std::vector<Node> nodes;
  std::vector<Segment> segments;
};

bool on(const cv::Mat& s, int x, int y) {
  return x >= 0 && y >= 0 && x < s.cols && y < s.rows && s.at<std::uint8_t>(y, x) != 0;
}

bool isolated(const cv::Mat& s, int x, int y) {
  for (const auto& d : kSteps) {
    if (on(s, x + d[0], y + d[1])) return false;
  }
  return true;
}

Graph build_graph(const cv::Mat& s) {
  Graph g;
  cv::Mat node_id(s.size(), CV_32S, cv::Scalar(-1));
  cv::Mat fork = cv::Mat::zeros(s.size(), CV_8U);
  // A skeleton covers a few per cent of the image: visit its pixels, not the whole grid.
  std::vector<cv::Point> skeleton_px, fork_px;
  cv::findNonZero(s, skeleton_px);
  for (const cv::Point p : skeleton_px) {
    const int c = crossing_number(s, p.x, p.y);
    if (c >= 3) {
      fork.at<std::uint8_t>(p) = 1;
      fork_px.push_back(p);
    } else if (c == 1 || (c == 0 && isolated(s, p.x, p.y))) {  // isolated: zero-length valley
      node_id.at<int>(p) = static_cast<int>(g.nodes.size());
      g.nodes.push_back({{p}, cv::Point2d(p.x, p.y), true, {}});
    }
  }
  // Adjacent fork pixels are one fork.
  cv::Mat labels;
  const int n = fork_px.empty() ? 1 : cv::connectedComponents(fork, labels, 8, CV_32S);
  const int first_fork = static_cast<int>(g.nodes.size());
  g.nodes.resize(g.nodes.size() + static_cast<std::size_t>(std::max(0, n - 1)));
  for (const cv::Point p : fork_px) {
    const int id = first_fork + labels.at<int>(p) - 1;
    node_id.at<int>(p) = id;
    g.nodes[static_cast<std::size_t>(id)].pixels.push_back(p);
  }
  for (auto& node : g.nodes) {
    cv::Point2d sum(0, 0);
    for (const auto& p : node.pixels) sum += cv::Point2d(p.x, p.y);
    node.centre = sum / static_cast<double>(node.pixels.size());
  }
  // Walk from every node pixel along unvisited valley pixels to the next node.
  cv::Mat visited = cv::Mat::zeros(s.size(), CV_8U);
  auto step = [](cv::Point a, cv::Point b) {
    return (a.x != b.x && a.y != b.y) ? std::sqrt(2.0) : 1.0;
  };
  for (int start = 0; start < static_cast<int>(g.nodes.size()); ++start) {
    for (const cv::Point from : g.nodes[static_cast<std::size_t>(start)].pixels) {
      for (const auto& d : kSteps) {
        cv::Point cur(from.x + d[0], from.y + d[1]);
        if (!on(s, cur.x, cur.y)) continue;
        const int other = node_id.at<int>(cur);
        Segment seg;
        seg.a = start;
        seg.path = {from};
        if (other >= 0) {
          // Two nodes touching: a segment without interior, recorded once.
          if (other <= start) continue;
          seg.b = other;
          seg.path.push_back(cur);
        } else {
          if (visited.at<std::uint8_t>(cur)) continue;
          while (true) {
            visited.at<std::uint8_t>(cur) = 1;
            seg.path.push_back(cur);
            seg.interior.push_back(cur);
            cv::Point next(-1, -1);
            bool ended = false;
            for (const auto& e : kSteps) {
              const cv::Point q(cur.x + e[0], cur.y + e[1]);
              if (!on(s, q.x, q.y)) continue;
              const int id = node_id.at<int>(q);
              // Back at the start node only after leaving it: a loop.
              if (id >= 0 && (id != start || seg.interior.size() >= 3)) {
                seg.b = id;
                seg.path.push_back(q);
                ended = true;
                break;
              }
              if (id < 0 && !visited.at<std::uint8_t>(q) && next.x < 0) next = q;
            }
            if (ended || next.x < 0) break;
            cur = next;
          }
        }
        for (std::size_t i = 1; i < seg.path.size(); ++i) {
          seg.length_px += step(seg.path[i - 1], seg.path[i]);
        }
        const int id = static_cast<int>(g.segments.size());
        g.nodes[static_cast<std::size_t>(seg.a)].segments.push_back(id);
        if (seg.b >= 0 && seg.b != seg.a) {
          g.nodes[static_cast<std::size_t>(seg.b)].segments.push_back(id);
        }
        g.segments.push_back(std::move(seg));
      }
    }
  }
  return g;
}

// Unit vector from `node` towards the point `reach_px` along segment `seg` (or its far end).
cv::Point2d direction_along(const Graph& g, int seg, int node, double reach_px) {
  const Segment& s = g.segments[static_cast<std::size_t>(seg)];
  const cv::Point2d c = g.nodes[static_cast<std::size_t>(node)].centre;
  const auto n = s.path.size();
  const std::size_t k = std::min(n - 1, static_cast<std::size_t>(std::max(1.0, reach_px)));
  const cv::Point p = s.a == node ? s.path[k] : s.path[n - 1 - k];
  cv::Point2d d(p.x - c.x, p.y - c.y);
  const double len = std::hypot(d.x, d.y);
  return len > 0 ? d / len : cv::Point2d(0, 0);
}

void erase(cv::Mat& s, const std::vector<cv::Point>& pixels) {
  for (const auto& p : pixels) s.at<std::uint8_t>(p) = 0;
}

// Angle between two axes (directions modulo pi), in [0, pi/2].
double axis_angle(double a, double b) {
  const double d = std::fmod(std::abs(a - b), std::numbers::pi);
  return std::min(d, std::numbers::pi - d);
}

int join_gaps(cv::Mat& s, const Graph& g, double px_per_mm, const SkeletonRepairParams& p) {
  const double reach = p.direction_mm * px_per_mm;
  const double max_gap = p.gap_max_mm * px_per_mm;
  struct End {
    cv::Point at;
    cv::Point2d pointing;
    int segment;
  };
  std::vector<End> ends;
  for (int i = 0; i < static_cast<int>(g.nodes.size()); ++i) {
    const Node& n = g.nodes[static_cast<std::size_t>(i)];
    if (!n.ending || n.segments.size() != 1) continue;
    // An ending points away from the valley it ends.
    ends.push_back({n.pixels[0], -direction_along(g, n.segments[0], i, reach), n.segments[0]});
  }
  // Sorted by x, so that each ending is compared only with those within reach along x.
  std::sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.at.x < b.at.x; });
  struct Pair {
    double d;
    std::size_t i, j;
  };
  std::vector<Pair> pairs;
  const double cos_max = std::cos(p.gap_max_angle_rad);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = i + 1; j < ends.size() && ends[j].at.x - ends[i].at.x < max_gap; ++j) {
      if (ends[i].segment == ends[j].segment) continue;
      const cv::Point2d v(ends[j].at.x - ends[i].at.x, ends[j].at.y - ends[i].at.y);
      const double d = std::hypot(v.x, v.y);
      if (d <= 0 || d >= max_gap) continue;
      if (ends[i].pointing.dot(v / d) < cos_max || ends[j].pointing.dot(-v / d) < cos_max) {
        continue;
      }
      pairs.push_back({d, i, j});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d < b.d; });
  std::vector<char> used(ends.size(), 0);
  int joined = 0;
  for (const Pair& pr : pairs) {
    if (used[pr.i] || used[pr.j]) continue;
    used[pr.i] = used[pr.j] = 1;
    const cv::Point a = ends[pr.i].at, b = ends[pr.j].at;
    cv::line(s, a, b, cv::Scalar(1), 1, cv::LINE_8);
    // A drawn join can leave a staircase corner at its ends that reads as a fork: thin again
    // around it only (a whole-image pass would double the cost of the thinning). The window's
    // outer pixels see a cut-off neighbourhood, so only its inner part is written back.
    constexpr int kMargin = 4;
    const cv::Rect image(0, 0, s.cols, s.rows);
    const cv::Rect box(std::min(a.x, b.x), std::min(a.y, b.y), std::abs(a.x - b.x) + 1,
                       std::abs(a.y - b.y) + 1);
    const cv::Rect outer =
        (box + cv::Size(4 * kMargin, 4 * kMargin) - cv::Point(2 * kMargin, 2 * kMargin)) & image;
    const cv::Rect inner =
        (box + cv::Size(2 * kMargin, 2 * kMargin) - cv::Point(kMargin, kMargin)) & image;
    const cv::Mat thinned = zhang_suen_thinning(s(outer));
    thinned(inner - outer.tl()).copyTo(s(inner));
    ++joined;
  }
  return joined;
}

// One round of removals; each node takes part in at most one, since a removal changes what
// its node is (a fork losing a branch becomes a plain valley point).
SkeletonRepairCounts remove_round(cv::Mat& s, const Graph& g, double px_per_mm,
                                  const SkeletonRepairParams& p) {
  SkeletonRepairCounts counts;
  std::vector<char> touched(g.nodes.size(), 0);
  for (const Node& n : g.nodes) {
    if (n.ending && n.segments.empty()) {
      erase(s, n.pixels);
      ++counts.short_valleys;
    }
  }
  const double reach = p.direction_mm * px_per_mm;
  auto node = [&](int i) -> const Node& { return g.nodes[static_cast<std::size_t>(i)]; };
  // Shortest first: at a fork with two short arms, the shorter one is the spur.
  std::vector<int> order(g.segments.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return g.segments[static_cast<std::size_t>(a)].length_px <
           g.segments[static_cast<std::size_t>(b)].length_px;
  });
  for (const int si : order) {
    const Segment& seg = g.segments[static_cast<std::size_t>(si)];
    if (seg.b < 0 || seg.a == seg.b || touched[static_cast<std::size_t>(seg.a)] ||
        touched[static_cast<std::size_t>(seg.b)]) {
      continue;
    }
    const Node& a = node(seg.a);
    const Node& b = node(seg.b);
    const double len_mm = seg.length_px / px_per_mm;
    bool removed = false;
    if (a.ending && b.ending) {
      if (len_mm < p.short_valley_max_mm) {
        erase(s, seg.path);
        ++counts.short_valleys;
        removed = true;
      }
    } else if (a.ending != b.ending) {
      const Node& fork = a.ending ? b : a;
      const Node& end = a.ending ? a : b;
      if (len_mm < p.spur_max_mm && fork.segments.size() >= 3) {
        erase(s, seg.interior);
        erase(s, end.pixels);
        ++counts.spurs;
        removed = true;
      }
    } else if (len_mm < p.bridge_max_mm && a.segments.size() >= 3 && b.segments.size() >= 3) {
      // Valley axis at the two forks from their other branches (doubled angles: an axis has
      // no sign), against the axis of the segment itself.
      double cx = 0, cy = 0;
      for (const int end_id : {seg.a, seg.b}) {
        for (const int other : node(end_id).segments) {
          if (other == si) continue;
          const cv::Point2d d = direction_along(g, other, end_id, reach);
          const double t = std::atan2(d.y, d.x);
          cx += std::cos(2 * t);
          cy += std::sin(2 * t);
        }
      }
      const double valley_axis = 0.5 * std::atan2(cy, cx);
      const double seg_axis = std::atan2(b.centre.y - a.centre.y, b.centre.x - a.centre.x);
      if (std::hypot(cx, cy) > 0 && axis_angle(valley_axis, seg_axis) > p.bridge_min_angle_rad) {
        erase(s, seg.interior);
        ++counts.bridges;
        removed = true;
      }
    }
    if (removed) {
      touched[static_cast<std::size_t>(seg.a)] = 1;
      touched[static_cast<std::size_t>(seg.b)] = 1;
    }
  }
  return counts;
}

}  // namespace

SkeletonRepairCounts repair_skeleton(cv::Mat& skeleton, double px_per_mm,
                                     const SkeletonRepairParams& params) {
  SkeletonRepairCounts total;
  if (skeleton.empty()) return total;
  skeleton.setTo(1, skeleton > 1);
  // Tracing the graph is most of the cost: it is traced again only after a change.
  Graph graph = build_graph(skeleton);
  total.gaps_joined = join_gaps(skeleton, graph, px_per_mm, params);
  if (total.gaps_joined > 0) graph = build_graph(skeleton);
  // Each round removes at least one segment or stops; a few rounds suffice in practice, the
  // bound only guards against a pathological skeleton.
  for (int round = 0; round < 8; ++round) {
    if (round > 0) graph = build_graph(skeleton);
    const SkeletonRepairCounts c = remove_round(skeleton, graph, px_per_mm, params);
    total.spurs += c.spurs;
    total.short_valleys += c.short_valleys;
    total.bridges += c.bridges;
    if (c.spurs + c.short_valleys + c.bridges == 0) break;
  }
  return total;
}

}  // namespace tactile::capture
