#pragma once
// Disjoint sets over 0..n-1 with one rule callers can rely on: the representative of a set is
// its lowest index (so results do not depend on the order of unions). Path halving keeps finds
// short; without union by rank a find is O(log n) amortised, plenty for meshes and complexes.
#include <medax/geometry.hpp>

#include <numeric>
#include <vector>

namespace medax {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) : parent_(n) { std::iota(parent_.begin(), parent_.end(), Index{0}); }

  std::size_t size() const { return parent_.size(); }
  /// Adds a singleton set and returns its index.
  Index add() {
    parent_.push_back(static_cast<Index>(parent_.size()));
    return parent_.back();
  }
  /// The lowest index of x's set.
  Index find(Index x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Merges the sets of a and b; false when they were one set already.
  bool unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (a < b) parent_[b] = a;
    else parent_[a] = b;
    return true;
  }
  /// The number of sets.
  std::size_t count() {
    std::size_t n = 0;
    for (Index x = 0; x < parent_.size(); ++x) n += find(x) == x;
    return n;
  }

 private:
  std::vector<Index> parent_;
};

}  // namespace medax
