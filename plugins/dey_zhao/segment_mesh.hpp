#pragma once
// Does a segment meet a triangle mesh? The exact answer of CGAL::do_intersect(Triangle_3,
// Segment_3) over every (non-degenerate) triangle, found fast: a bounding-volume hierarchy with
// boxes culls conservatively, and the triangles left are tested with exact orientations
// (CGAL's statically filtered predicates), calling CGAL's do_intersect only for the touching
// cases. Internal to the dey_zhao package (the `mesh` inner selection).
#include <medax/surface.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace medax::dey_zhao {

class SegmentMeshTest {
 public:
  /// The mesh's triangles but the collinear ones (no interior to meet).
  explicit SegmentMeshTest(const SurfaceMesh& mesh);

  /// True when the closed segment [a, b] meets a triangle (closed) of the mesh. Thread-safe.
  bool meets(const Vec3& a, const Vec3& b) const;

  std::size_t num_triangles() const { return triangles_.size(); }

 private:
  /// A subtree: `count` triangles from `first` (a leaf), or (count 0) the node nodes_[first].
  struct Ref {
    std::uint32_t first, count;
  };
  /// An inner node: up to four children (two levels of median splits), their boxes
  /// ([axis][child], so that they are tested together; widened by the slab test's margin).
  struct Node {
    double lo[3][4], hi[3][4];
    Ref child[4];
    int slots;  ///< bit k: child k exists
  };
  using Triangle = std::array<Vec3, 3>;
  /// A triangle (a, b, c) with what its plane test needs: the 2×2 minors of (b − a, c − a), i.e.
  /// the normal (b − a) × (c − a) as floating-point evaluates it, and per component the sum of
  /// the two products' magnitudes (for the error bound).
  struct Plane {
    Vec3 normal, magnitude;
  };
  struct Box {
    Vec3 lo, hi;
  };

  /// Builds the subtree of the triangles order[begin, end), returns it and its box.
  Ref build(std::uint32_t begin, std::uint32_t end, std::vector<std::uint32_t>& order, const std::vector<Vec3>& centroids,
            const std::vector<Triangle>& triangles, Box& box);
  /// Sets the node's child k and its box, widened by the slab test's margin for the mesh's extent.
  void set_child(Node& n, int k, Ref child, const Box& box) const;
  /// The leaf's triangles: does one meet [a, b]?
  bool leaf_meets(Ref leaf, const Vec3& a, const Vec3& b) const;

  Node top_{};  ///< above the root: its only child is the root
  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;  ///< in leaf order
  std::vector<Plane> planes_;        ///< of triangles_
  double extent_ = 0;                ///< the largest |coordinate| of a triangle corner
};

}  // namespace medax::dey_zhao
