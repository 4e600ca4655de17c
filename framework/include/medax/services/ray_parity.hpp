#pragma once
// Exact inside/outside classification of many points against a closed triangle mesh, by the
// parity of the crossings of an axis-parallel ray (+x or -x, whichever meets fewer triangles)
// with the mesh. Triangles are bucketed in a grid over (y, z), so a query only looks at the
// triangles of its column. Every sign is an
// exact CGAL predicate; rays through an edge or a vertex are resolved by symbolic perturbation
// of the query in (y, z), so there is no degenerate case and no retry. A point on the surface
// counts as outside, as with InsideTest (inside.hpp). Used by the voronoi and dey_zhao
// extractions; moved here from plugins/voronoi so both share one copy.
#include <medax/surface.hpp>

#include <array>
#include <vector>

namespace medax::services {

class RayParityInside {
 public:
  /// Throws std::invalid_argument when the mesh is not closed (an edge with an odd number of
  /// faces), since inside/outside is then undefined. Orientation does not matter.
  /// `columns_per_triangle` sets the grid resolution (a speed knob only).
  explicit RayParityInside(const SurfaceMesh& mesh, double columns_per_triangle = 0.25);

  /// True when p is strictly inside.
  bool inside(const Vec3& p) const;
  /// Classifies many points (in parallel when `parallel`).
  std::vector<char> inside(const std::vector<Vec3>& points, bool parallel = true) const;

  std::size_t num_columns() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  std::size_t num_entries() const { return entries_.size(); }

 private:
  struct Triangle {
    Vec3 a, b, c;
    int projected_sign;  ///< exact sign of the (y, z) projection's orientation (n_x)
  };
  /// One triangle in one grid column, with its bounding box (rounded outwards to float: a
  /// conservative, compact first test); `x` is the box's xmax.
  struct Entry {
    float ymin, ymax, zmin, zmax, x;
    Index triangle;
  };
  /// x range of a column's triangles, and their largest x extent.
  struct ColumnX {
    float lo, hi, extent;
  };

  // The constructor's steps: the triangles and their boxes, the (y, z) grid, the columns each
  // box covers, the triangles renumbered by their first column, the columns' entries.
  void set_triangles(const SurfaceMesh& mesh, std::vector<Entry>& boxes, std::vector<float>& box_xmin);
  void set_grid(const SurfaceMesh& mesh, double columns_per_triangle);
  std::vector<std::array<int, 4>> column_ranges(const std::vector<Entry>& boxes) const;
  void renumber_by_column(std::vector<Entry>& boxes, std::vector<float>& box_xmin,
                          std::vector<std::array<int, 4>>& ranges);
  void fill_columns(const std::vector<Entry>& boxes, const std::vector<float>& box_xmin,
                    const std::vector<std::array<int, 4>>& ranges);

  static constexpr std::size_t kNoColumn = ~std::size_t{0};
  /// The grid column of q, or kNoColumn when q is outside the mesh's bounding box.
  std::size_t column(const Vec3& q) const;
  bool inside_column(const Vec3& q, std::size_t column) const;
  /// Crossing parity of the ray from q along `direction` (+1 or -1) times x.
  template <int direction>
  bool parity(const Vec3& q, std::size_t column) const;

  std::vector<Triangle> triangles_;
  std::vector<Entry> entries_;         ///< per column, by decreasing xmax
  std::vector<std::size_t> offsets_;   ///< column c holds entries_[offsets_[c], offsets_[c + 1])
  std::vector<ColumnX> columns_x_;
  double y0_ = 0, z0_ = 0, inv_hy_ = 0, inv_hz_ = 0;
  int ny_ = 0, nz_ = 0;
  double y1_ = 0, z1_ = 0, xmin_ = 0, xmax_ = 0;
};

}  // namespace medax::services
