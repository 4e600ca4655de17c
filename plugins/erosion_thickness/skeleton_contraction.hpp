#pragma once
// Internal to et_skeleton: which cells are protected (kept), and the contraction of the free
// pairs outside them.
#include "skeleton_cells.hpp"

#include <cstdint>
#include <queue>
#include <tuple>
#include <vector>

namespace medax::et::skeleton {

/// The closure of the protected cells: what the contraction must keep.
struct Kept {
  std::vector<char> w, e, v;
};

/// The protected wedges and curve 1-cells and their closure; counts them in `out`.
Kept protect(const Subdivision& sub, const CellComplex& k, const SkeletonOptions& options, Skeleton& out);

/// A free pair (sigma, tau) of phase 1, with its key.
struct Pair {
  int phase;  // 0: neither cell is a medial-curve edge; 1: one is (those go last)
  double prio_tau, prio_sigma;
  int type;  // 0: (1-cell, 2-cell), 1: (0-cell, 1-cell)
  Index sigma, tau;
};
struct PairLater {
  bool operator()(const Pair& a, const Pair& b) const {
    return std::tie(a.phase, a.prio_tau, a.prio_sigma, a.type, a.tau, a.sigma) >
           std::tie(b.phase, b.prio_tau, b.prio_sigma, b.type, b.tau, b.sigma);
  }
};

/// Removes free pairs (sigma, tau) outside the kept cells until none is left (Liu et al. 2010).
/// Three queues, popped in this order, give the order (phase, prio tau, prio sigma, type, tau,
/// sigma) with small entries: phase-0 (0-cell, 1-cell) pairs (prio tau = -inf) keyed by
/// (1-cell, 0-cell); phase-0 (1-cell, wedge) pairs (prio sigma = -inf) keyed by (rank of the
/// wedge by (prio, id), 1-cell); phase-1 pairs with their full key.
class Contraction {
 public:
  Contraction(const CellComplex& k, const Kept& kept, Index num_vertices, std::size_t np);
  void run();

  std::vector<char> w_alive, e_alive, v_alive;
  std::vector<Index> e_count, v_count;  ///< surviving cofaces of a 1-cell, of a point

 private:
  using Key = std::uint64_t;

  /// Wedges ranked by (their face's priority, id): the key of the phase-0 wedge pairs.
  void rank_wedges();
  void try_edge_wedge(Index e);
  void try_vertex_edge(Index v);
  void collapse_wedge(Index e, Index w);
  void collapse_vertex(Index v, Index e);

  const CellComplex& k_;
  const Kept& kept_;
  std::vector<Index> wedge_rank_, wedge_of_rank_;
  std::priority_queue<Key, std::vector<Key>, std::greater<>> vertex_pairs_, wedge_pairs_;
  std::priority_queue<Pair, std::vector<Pair>, PairLater> curve_pairs_;
  // Phase-1 pairs are only queued once phase 0 has run dry (then every free one is found by a
  // scan): queued earlier, most would be stale by then and only slow the queue down.
  bool curves_active_ = false;
};

}  // namespace medax::et::skeleton
