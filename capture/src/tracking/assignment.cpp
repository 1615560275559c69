#include "tracking/assignment.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace tactile::capture {

namespace {

bool higher(const ScoredPair& l, const ScoredPair& r) {
  if (l.score != r.score) return l.score > r.score;
  if (l.left != r.left) return l.left < r.left;
  return l.right < r.right;
}

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Minimum-cost perfect assignment of an n x n cost matrix (row-major); returns the column of
// each row. Shortest augmenting paths with potentials, O(n^3).
std::vector<int> hungarian(const std::vector<double>& cost, int n) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<std::size_t>(n) + 1, 0), v(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> p(static_cast<std::size_t>(n) + 1, 0), way(static_cast<std::size_t>(n) + 1, 0);
  auto at = [&](int i, int j) {
    return cost[static_cast<std::size_t>(i - 1) * static_cast<std::size_t>(n) +
                static_cast<std::size_t>(j - 1)];
  };
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(n) + 1, inf);
    std::vector<char> used(static_cast<std::size_t>(n) + 1, 0);
    do {
      used[static_cast<std::size_t>(j0)] = 1;
      const int i0 = p[static_cast<std::size_t>(j0)];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= n; ++j) {
        const auto uj = static_cast<std::size_t>(j);
        if (used[uj]) continue;
        const double cur = at(i0, j) - u[static_cast<std::size_t>(i0)] - v[uj];
        if (cur < minv[uj]) {
          minv[uj] = cur;
          way[uj] = j0;
        }
        if (minv[uj] < delta) {
          delta = minv[uj];
          j1 = j;
        }
      }
      for (int j = 0; j <= n; ++j) {
        const auto uj = static_cast<std::size_t>(j);
        if (used[uj]) {
          u[static_cast<std::size_t>(p[uj])] += delta;
          v[uj] -= delta;
        } else {
          minv[uj] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<std::size_t>(j0)] != 0);
    do {
      const int j1 = way[static_cast<std::size_t>(j0)];
      p[static_cast<std::size_t>(j0)] = p[static_cast<std::size_t>(j1)];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column_of_row(static_cast<std::size_t>(n), -1);
  for (int j = 1; j <= n; ++j) {
    column_of_row[static_cast<std::size_t>(p[static_cast<std::size_t>(j)] - 1)] = j - 1;
  }
  return column_of_row;
}

}  // namespace

std::vector<ScoredPair> assign_greedy(std::vector<ScoredPair> candidates) {
  std::sort(candidates.begin(), candidates.end(), higher);
  std::size_t lefts = 0, rights = 0;
  for (const auto& c : candidates) {
    lefts = std::max(lefts, c.left + 1);
    rights = std::max(rights, c.right + 1);
  }
  std::vector<char> left_used(lefts, 0), right_used(rights, 0);
  std::vector<ScoredPair> chosen;
  for (const auto& c : candidates) {
    if (left_used[c.left] || right_used[c.right]) continue;
    left_used[c.left] = right_used[c.right] = 1;
    chosen.push_back(c);
  }
  return chosen;
}

std::vector<ScoredPair> assign_optimal(const std::vector<ScoredPair>& candidates) {
  // Dense local indices: lefts first, then rights, as nodes of one candidate graph.
  std::unordered_map<std::size_t, std::size_t> left_node, right_node;
  for (const auto& c : candidates) {
    left_node.emplace(c.left, left_node.size());
  }
  for (const auto& c : candidates) {
    right_node.emplace(c.right, left_node.size() + right_node.size());
  }
  std::vector<std::size_t> parent(left_node.size() + right_node.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (const auto& c : candidates) {
    const std::size_t a = find_root(parent, left_node[c.left]);
    const std::size_t b = find_root(parent, right_node[c.right]);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  // Candidates grouped by connected component; each group is solved on its own.
  std::unordered_map<std::size_t, std::vector<ScoredPair>> groups;
  for (const auto& c : candidates) groups[find_root(parent, left_node[c.left])].push_back(c);
  std::vector<ScoredPair> chosen;
  for (auto& [root, group] : groups) {
    if (group.size() == 1) {
      chosen.push_back(group.front());
      continue;
    }
    std::vector<std::size_t> lefts, rights;
    for (const auto& c : group) {
      lefts.push_back(c.left);
      rights.push_back(c.right);
    }
    std::sort(lefts.begin(), lefts.end());
    lefts.erase(std::unique(lefts.begin(), lefts.end()), lefts.end());
    std::sort(rights.begin(), rights.end());
    rights.erase(std::unique(rights.begin(), rights.end()), rights.end());
    const int n = static_cast<int>(std::max(lefts.size(), rights.size()));
    // Cost -score for a candidate, 0 for "not matched" (padding or a non-candidate pair), so the
    // minimum-cost assignment maximises the total score.
    std::vector<double> cost(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0);
    std::vector<const ScoredPair*> pair_at(cost.size(), nullptr);
    for (const auto& c : group) {
      const auto i = static_cast<std::size_t>(std::lower_bound(lefts.begin(), lefts.end(), c.left) -
                                              lefts.begin());
      const auto j = static_cast<std::size_t>(
          std::lower_bound(rights.begin(), rights.end(), c.right) - rights.begin());
      const std::size_t k = i * static_cast<std::size_t>(n) + j;
      if (!pair_at[k] || higher(c, *pair_at[k])) {
        cost[k] = -c.score;
        pair_at[k] = &c;
      }
    }
    const std::vector<int> column = hungarian(cost, n);
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(n) +
                            static_cast<std::size_t>(column[static_cast<std::size_t>(i)]);
      if (pair_at[k]) chosen.push_back(*pair_at[k]);
    }
  }
  std::sort(chosen.begin(), chosen.end(), higher);
  return chosen;
}

}  // namespace tactile::capture
