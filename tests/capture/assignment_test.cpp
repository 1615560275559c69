// Greedy and optimal one-to-one assignment, the optimal one against exhaustive search.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <set>

#include "tracking/assignment.hpp"

namespace tactile::capture {
namespace {

double total(const std::vector<ScoredPair>& pairs) {
  double sum = 0;
  for (const auto& p : pairs) sum += p.score;
  return sum;
}

void expect_one_to_one(const std::vector<ScoredPair>& pairs) {
  std::set<std::size_t> lefts, rights;
  for (const auto& p : pairs) {
    EXPECT_TRUE(lefts.insert(p.left).second) << "left " << p.left << " used twice";
    EXPECT_TRUE(rights.insert(p.right).second) << "right " << p.right << " used twice";
  }
}

// Best total score over every one-to-one subset of the candidates (small inputs only).
double exhaustive_best(const std::vector<ScoredPair>& c) {
  double best = 0;
  std::set<std::size_t> lefts, rights;
  std::function<void(std::size_t, double)> walk = [&](std::size_t i, double sum) {
    best = std::max(best, sum);
    if (i == c.size()) return;
    walk(i + 1, sum);
    if (!lefts.count(c[i].left) && !rights.count(c[i].right)) {
      lefts.insert(c[i].left);
      rights.insert(c[i].right);
      walk(i + 1, sum + c[i].score);
      lefts.erase(c[i].left);
      rights.erase(c[i].right);
    }
  };
  walk(0, 0);
  return best;
}

TEST(Assignment, OptimalBeatsGreedyWhereTheBestPairBlocksTwoGoodOnes) {
  const std::vector<ScoredPair> c{{0.9, 0, 0}, {0.8, 0, 1}, {0.7, 1, 0}};
  const auto greedy = assign_greedy(c);
  ASSERT_EQ(greedy.size(), 1u);
  EXPECT_DOUBLE_EQ(total(greedy), 0.9);
  const auto optimal = assign_optimal(c);
  ASSERT_EQ(optimal.size(), 2u);
  EXPECT_DOUBLE_EQ(total(optimal), 1.5);
  EXPECT_EQ(optimal[0].left, 0u);  // decreasing score
  EXPECT_EQ(optimal[0].right, 1u);
}

TEST(Assignment, OptimalMatchesExhaustiveSearchOnRandomCandidateSets) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> score(0.01, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<ScoredPair> c;
    const int n = 1 + trial % 12;
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (int k = 0; k < n; ++k) {
      // Sparse, unevenly numbered indices, as tracks and features are.
      const std::size_t l = 10 * (rng() % 5), r = 7 + rng() % 6;
      if (seen.insert({l, r}).second) c.push_back({score(rng), l, r});
    }
    const auto optimal = assign_optimal(c);
    expect_one_to_one(optimal);
    expect_one_to_one(assign_greedy(c));
    EXPECT_NEAR(total(optimal), exhaustive_best(c), 1e-12) << "trial " << trial;
    EXPECT_GE(total(optimal) + 1e-12, total(assign_greedy(c)));
  }
}

TEST(Assignment, NoCandidatesNoPairs) {
  EXPECT_TRUE(assign_greedy({}).empty());
  EXPECT_TRUE(assign_optimal({}).empty());
}

}  // namespace
}  // namespace tactile::capture
