#pragma once
// Sphere splitting (notes §2.9): clusters in descending order of error; a cluster is split when
// its error passes the threshold (error mode) or the target count is not reached (count mode),
// and no adjacent cluster has been split in this round (a greedy independent set). At most
// min(⌈fraction·|M|⌉, max_per_round) splits per round.
#include "dual.hpp"

#include <vector>

namespace medax::vmas {

struct SplitRound {
  bool count_mode = true;
  std::size_t target = 100;    ///< count mode: stop splitting at this many spheres
  double threshold = 2.5e-4;   ///< error mode: split only clusters with E(C) ≥ threshold (absolute)
  double fraction = 0.2;
  std::size_t max_per_round = 10;
};

/// The clusters to split this round, in the order chosen.
std::vector<Index> select_splits(const std::vector<double>& errors, const Adjacency& adjacency,
                                 const SplitRound& round);

}  // namespace medax::vmas
