#pragma once
// Private: one-to-one assignment between two sets (tracks and features) from scored candidate
// pairs: greedy by decreasing score, or optimal (maximum total score, Hungarian method on each
// connected group of candidates).

#include <cstddef>
#include <vector>

namespace tactile::capture {

struct ScoredPair {
  double score;  // > 0
  std::size_t left;
  std::size_t right;
};

// Chosen pairs (each left and each right at most once), in decreasing score (ties: left, right).
std::vector<ScoredPair> assign_greedy(std::vector<ScoredPair> candidates);
std::vector<ScoredPair> assign_optimal(const std::vector<ScoredPair>& candidates);

}  // namespace tactile::capture
