#include "inner.hpp"

#include "segment_mesh.hpp"

#include <medax/services/ray_parity.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <deque>
#include <stdexcept>

namespace medax::dey_zhao {

using services::DelaunayTetrahedralization;

// ---------------------------------------------------------------------------------------------
// (a) Delaunay mesh triangles: wall-parity flood fill over the cells.

namespace {

/// The cells around each point (CSR), for finding the cells of a facet.
struct IncidentCells {
  std::vector<std::uint32_t> offsets, cells;
  explicit IncidentCells(const DelaunayTetrahedralization& dt) : offsets(dt.point_vertex.size() + 1, 0) {
    const std::size_t np = dt.point_vertex.size();
    for (const auto& c : dt.cells)
      for (Index x : c) ++offsets[x + 1];
    for (std::size_t i = 0; i < np; ++i) offsets[i + 1] += offsets[i];
    cells.resize(offsets[np]);
    std::vector<std::uint32_t> cursor(offsets.begin(), offsets.end() - 1);
    for (std::size_t c = 0; c < dt.cells.size(); ++c)
      for (Index x : dt.cells[c]) cells[cursor[x]++] = static_cast<std::uint32_t>(c);
  }
};

/// Wall bits: bit k of wall[c] when the facet of c opposite corner k is a mesh triangle (mod 2,
/// so a triangle given twice cancels, as it does for a ray-parity inside test). Counts in
/// `missing` the triangles that are no Delaunay facet.
std::vector<std::uint8_t> mesh_walls(const DelaunayTetrahedralization& dt, const SurfaceMesh& mesh,
                                     std::size_t& missing) {
  const std::size_t np = dt.point_vertex.size();
  const IncidentCells incident(dt);
  const auto rep = [&](Index v) { return v < np ? dt.vertex_point[dt.point_vertex[v]] : Index(~0u); };
  std::vector<std::uint8_t> wall(dt.cells.size(), 0);
  for (const Tri& f : mesh.faces) {
    const Index a = rep(f[0]), b = rep(f[1]), c = rep(f[2]);
    if (a >= np || b >= np || c >= np) {
      ++missing;
      continue;
    }
    if (a == b || b == c || a == c) continue;  // degenerate face: no area, no wall
    bool found = false;
    for (std::uint32_t k = incident.offsets[a]; k < incident.offsets[a + 1] && !found; ++k) {
      const std::uint32_t cell = incident.cells[k];
      const auto& corner = dt.cells[cell];
      int hit = 0, opposite = -1;
      for (int j = 0; j < 4; ++j) {
        if (corner[j] == a || corner[j] == b || corner[j] == c) ++hit;
        else opposite = j;
      }
      if (hit != 3) continue;
      found = true;
      wall[cell] ^= static_cast<std::uint8_t>(1u << opposite);
      const std::int64_t other = dt.neighbours[cell][opposite];
      if (other != DelaunayTetrahedralization::kInfinite)
        for (int j = 0; j < 4; ++j)
          if (dt.neighbours[other][j] == static_cast<std::int64_t>(cell)) wall[other] ^= static_cast<std::uint8_t>(1u << j);
    }
    if (!found) ++missing;
  }
  return wall;
}

/// Parity labels of the cells: 0 outside the hull, flipped by every wall crossed; throws when two
/// paths disagree (the walls bound no closed surface).
std::vector<signed char> flood_parity(const DelaunayTetrahedralization& dt, const std::vector<std::uint8_t>& wall) {
  const std::size_t n = dt.cells.size();
  std::vector<signed char> label(n, -1);
  std::vector<std::uint32_t> queue;
  queue.reserve(n);
  const auto reach = [&](std::size_t c, signed char l) {
    if (label[c] == -1) {
      label[c] = l;
      queue.push_back(static_cast<std::uint32_t>(c));
    } else if (label[c] != l) {
      throw std::invalid_argument("inner selection: the mesh triangles are Delaunay facets but do not bound a "
                                  "closed surface (inconsistent inside parity); run the `repair` stage first");
    }
  };
  for (std::size_t c = 0; c < n; ++c)
    for (int k = 0; k < 4; ++k)
      if (dt.neighbours[c][k] == DelaunayTetrahedralization::kInfinite) reach(c, (wall[c] >> k) & 1);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t c = queue[head];
    for (int k = 0; k < 4; ++k) {
      const std::int64_t nb = dt.neighbours[c][k];
      if (nb != DelaunayTetrahedralization::kInfinite)
        reach(static_cast<std::size_t>(nb), static_cast<signed char>(label[c] ^ ((wall[c] >> k) & 1)));
    }
  }
  return label;
}

}  // namespace

bool label_cells_by_surface(const DelaunayTetrahedralization& dt, const SurfaceMesh& mesh, std::vector<char>& inside,
                            std::size_t& missing) {
  missing = 0;
  const std::vector<std::uint8_t> wall = mesh_walls(dt, mesh, missing);
  if (missing) return false;
  const std::vector<signed char> label = flood_parity(dt, wall);
  inside.assign(dt.cells.size(), 0);
  for (std::size_t c = 0; c < dt.cells.size(); ++c) inside[c] = label[c] == 1;
  return true;
}

// ---------------------------------------------------------------------------------------------
// (b) A general closed mesh: midpoint inside, shrunk segment free of the mesh.

struct MeshEdgeSide::Impl {
  services::RayParityInside parity;
  SegmentMeshTest segments;
  explicit Impl(const SurfaceMesh& mesh) : parity(mesh), segments(mesh) {}
};

MeshEdgeSide::MeshEdgeSide(const SurfaceMesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
MeshEdgeSide::~MeshEdgeSide() = default;
MeshEdgeSide::MeshEdgeSide(MeshEdgeSide&&) noexcept = default;
MeshEdgeSide& MeshEdgeSide::operator=(MeshEdgeSide&&) noexcept = default;

std::vector<char> MeshEdgeSide::inner(const std::vector<Vec3>& points, const std::vector<std::array<Index, 2>>& edges,
                                      bool parallel) const {
  std::vector<Vec3> midpoints(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) midpoints[i] = 0.5 * (points[edges[i][0]] + points[edges[i][1]]);
  std::vector<char> out = impl_->parity.inside(midpoints, parallel);
  const auto segment = [&](std::size_t i) {
    if (!out[i]) return;
    const Vec3& p = points[edges[i][0]];
    const Vec3& q = points[edges[i][1]];
    const Vec3 d = q - p;
    constexpr double kShrink = 1.0 / 16;  // a power of two keeps scaling exact
    if (impl_->segments.meets(p + kShrink * d, q - kShrink * d)) out[i] = 0;
  };
  if (parallel) tbb::parallel_for(std::size_t{0}, edges.size(), segment);
  else for (std::size_t i = 0; i < edges.size(); ++i) segment(i);
  return out;
}

}  // namespace medax::dey_zhao
