#pragma once
// Internal to MEDIAL (medial.cpp and the pass files umbrellas.cpp, selection.cpp,
// output_complex.cpp): the renumbered points, the selected edges with their rings, and the
// geometry the passes share.
#include "medial.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace medax::dey_zhao {

using services::DelaunayTetrahedralization;
inline constexpr std::int64_t kInf = DelaunayTetrahedralization::kInfinite;
inline constexpr Index kNone = ~Index{0};
inline constexpr std::size_t kBlock = 4096;  // cells per parallel work unit (fixed: output independent of the schedule)

/// The three corners of facet k of a cell, in increasing position order.
inline std::array<Index, 3> facet_corners(const std::array<Index, 4>& corner, int k) {
  std::array<Index, 3> f{};
  for (int j = 0, m = 0; j < 4; ++j)
    if (j != k) f[m++] = corner[j];
  return f;
}

/// Normal of facet k of a positively oriented cell, pointing out of the cell (not normalised).
/// The direction comes from the cell's orientation (exact), not from a floating-point test.
inline Vec3 outward_normal(const std::vector<Vec3>& P, const std::array<Index, 4>& corner, int k) {
  const auto f = facet_corners(corner, k);
  const Vec3 n = (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]);
  // (f0, f1, f2, corner k) is the permutation moving k last: sign (-1)^(3-k). When positive,
  // corner k is on the side n points to, so n points inwards.
  return (k % 2 == 1) ? Vec3(-n) : n;
}

inline Vec3 unit(const Vec3& v) {
  const double norm = v.norm();
  return norm > 0 ? Vec3(v / norm) : Vec3::Zero();
}

/// The points renumbered along a space-filling curve (locality): every pass runs on them, and
/// `original` maps back to the caller's indices for the output.
struct Renumbered {
  std::vector<Index> original;  ///< original[i]: the caller's index of point i
  std::vector<Vec3> P;
  bool has_normals = false;  ///< the input has one normal per point
  std::vector<Vec3> normals;  ///< ... renumbered
};

/// A selected Delaunay edge with the ring of cells around it, oriented along p → q.
struct Selected {
  Index p, q;
  EdgeScores scores;
  int bits;
  bool open;                  ///< unbounded facet: the ring is a chain between two hull facets
  std::uint32_t ring_begin, ring_size;
  std::int64_t first_ray = -1, last_ray = -1;  ///< open: hull facet (cell·4 + k) at the ring's front and back
};

/// A fixed-size array of a trivially copyable type whose storage is not initialised on
/// allocation: the caller constructs every element, and those writes (by parallel blocks) are
/// the pages' first touch, instead of one thread zero-filling a large fresh array first.
template <typename T>
class FreshArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  struct Free {
    std::size_t n = 0;
    void operator()(T* p) const { std::allocator<T>().deallocate(p, n); }
  };

 public:
  FreshArray() = default;
  explicit FreshArray(std::size_t n) : data_(std::allocator<T>().allocate(n), Free{n}), size_(n) {}
  /// Constructs element i as a copy of `value` (each element before it is read; again to replace it).
  void construct(std::size_t i, const T& value) { ::new (static_cast<void*>(data_.get() + i)) T(value); }
  std::size_t size() const { return size_; }
  const T* data() const { return data_.get(); }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  std::unique_ptr<T[], Free> data_;
  std::size_t size_ = 0;
};

/// The selected edges, in block order, with the rings of cells around them.
struct Selection {
  FreshArray<Selected> selected;
  FreshArray<Index> rings;  ///< selected[i]'s ring: ring_size cells from ring_begin
};

/// D–E. The conditions on every edge, from the lowest cell of its ring; rings of the selected.
Selection select_edges(const Renumbered& points, const services::DelaunayTetrahedralization& dt, const Umbrellas& u,
                       const MedialOptions& options, MedialReport& info);

/// The output complex from the kept facets: facets with shared Voronoi vertices,
/// fan-triangulated, and their closure.
MedialComplex build_complex(const Renumbered& points, const services::DelaunayTetrahedralization& dt,
                            const Selection& selection, const std::vector<char>& keep, const MedialOptions& options,
                            MedialReport& info);

}  // namespace medax::dey_zhao
