#include "interior_voronoi.hpp"

#include <medax/services/blocks.hpp>
#include <medax/services/delaunay.hpp>
#include <medax/services/delaunay_rings.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/ray_parity.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

namespace medax::voronoi {

namespace {

using services::DelaunayTetrahedralization;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr Index kNone = ~Index{0};
constexpr std::size_t kBlock = 2048;  // items per parallel work unit (fixed, so the output does not depend on the schedule)

/// An interior cell, in the compact numbering of the medial vertices: its corners and its four
/// neighbours (neighbour k across the facet opposite corner k), kNone when that neighbour is
/// infinite or exterior. 32 bytes, so a ring walk touches one cache line per step.
struct Node {
  std::array<Index, 4> corner;
  std::array<Index, 4> neighbour;
};

/// The triangles, fan diagonals and polygon count produced by one block of vertices.
struct FaceBlock {
  std::vector<Tri> faces;
  std::vector<Segment> diagonals;
  std::vector<int> polygon;  ///< per face, the polygon's number within the block
  int polygons = 0;
};

/// Voronoi polygons owned by the vertices [begin, end): for each Delaunay edge of the cell of
/// vertex i, the ring of cells around it, when it is finite, all interior, and i is its lowest
/// vertex. The ring is fan-triangulated from i.
void faces_of_block(const std::vector<Node>& nodes, Index begin, Index end, FaceBlock& out) {
  std::vector<Index> ring;
  const auto corners = [&](Index c) -> const std::array<Index, 4>& { return nodes[c].corner; };
  const auto neighbour = [&](Index c, int k) { return nodes[c].neighbour[k]; };
  for (Index i = begin; i < end; ++i) {
    const Node& node = nodes[i];
    for (const auto& e : services::kCellEdges) {
      // i's two neighbours in the ring around the edge are across the facets opposite the other
      // two corners: when one is lower or not interior (kNone is the highest), i owns no polygon.
      const Index left = node.neighbour[e[2]], right = node.neighbour[e[3]];
      if (left < i || right < i || left == kNone || right == kNone) continue;
      const Index u = node.corner[e[0]], w = node.corner[e[1]];
      ring.assign(1, i);
      // Owned when the ring closes without meeting a lower or exterior cell.
      if (services::walk_edge_ring(i, u, w, node.corner[e[2]], node.corner[e[3]], corners, neighbour, kNone, ring,
                                   4096) != services::RingEnd::Closed)
        continue;
      for (std::size_t k = 1; k + 1 < ring.size(); ++k) {
        out.faces.push_back({i, ring[k], ring[k + 1]});
        out.polygon.push_back(out.polygons);
        if (k >= 2) out.diagonals.push_back({i, ring[k]});
      }
      ++out.polygons;
    }
  }
}

/// 3. Compact: interior cells become vertices, in cell order (centre, radius, generators), and
/// their records in `nodes`. Returns the number of interior cells.
Index compact_cells(const DelaunayTetrahedralization& dt, const std::vector<char>& inside, bool parallel,
                    std::vector<Node>& nodes, MedialComplex& medial) {
  const std::size_t n = dt.cells.size();
  std::vector<Index> id(n, kNone);
  Index count = 0;
  for (std::size_t c = 0; c < n; ++c)
    if (inside[c]) id[c] = count++;

  nodes.resize(count);
  medial.centres.resize(count);
  medial.radii.resize(count);
  medial.generators.resize(count);
  services::for_blocks(n, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const Index i = id[c];
      if (i == kNone) continue;
      Node& node = nodes[i];
      node.corner = dt.cells[c];
      for (int k = 0; k < 4; ++k) {
        const std::int64_t nb = dt.neighbours[c][k];
        node.neighbour[k] = nb == DelaunayTetrahedralization::kInfinite ? kNone : id[nb];
      }
      medial.centres[i] = dt.circumcentres[c];
      medial.radii[i] = dt.circumradii[c];
      std::array<Index, 4> g = node.corner;
      std::sort(g.begin(), g.end());
      medial.generators[i].assign(g.begin(), g.end());
    }
  });
  return count;
}

/// 4. Voronoi edges: facets between two interior cells, each once (from its lower vertex).
void add_voronoi_edges(const std::vector<Node>& nodes, MedialComplex& medial) {
  const Index count = static_cast<Index>(nodes.size());
  medial.edges.reserve(2 * static_cast<std::size_t>(count));
  for (Index i = 0; i < count; ++i) {
    std::array<Index, 4> ends = nodes[i].neighbour;
    std::sort(ends.begin(), ends.end());  // kNone last
    for (Index j : ends)
      if (j > i && j != kNone) medial.edges.push_back({i, j});
  }
}

/// 5. Voronoi faces, fan-triangulated; their diagonals join the edges (after the Voronoi
/// edges, labelled kFanDiagonal). Returns the number of polygons.
std::size_t add_voronoi_faces(const std::vector<Node>& nodes, bool parallel, MedialComplex& medial) {
  const std::size_t count = nodes.size(), voronoi_edges = medial.edges.size();
  std::vector<FaceBlock> blocks(services::block_count(count, kBlock));
  services::for_blocks(count, kBlock, parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    faces_of_block(nodes, static_cast<Index>(begin), static_cast<Index>(end), blocks[b]);
  });
  std::size_t faces = 0, diagonals = 0;
  for (const FaceBlock& b : blocks) faces += b.faces.size(), diagonals += b.diagonals.size();
  medial.faces.reserve(faces);
  medial.edges.reserve(medial.edges.size() + diagonals);
  std::vector<int>& polygon = medial.add(kPolygon);
  polygon.reserve(faces);
  int polygons = 0;
  for (const FaceBlock& b : blocks) {
    medial.faces.insert(medial.faces.end(), b.faces.begin(), b.faces.end());
    medial.edges.insert(medial.edges.end(), b.diagonals.begin(), b.diagonals.end());
    for (int p : b.polygon) polygon.push_back(polygons + p);
    polygons += b.polygons;
  }
  std::vector<int>& diagonal = medial.add(kFanDiagonal);
  std::fill(diagonal.begin() + static_cast<std::ptrdiff_t>(voronoi_edges), diagonal.end(), 1);
  return static_cast<std::size_t>(polygons);
}

/// The inside test of a cloud without a mesh (InsideMethod::Normals): a circumcentre is inside
/// when it lies on the inner side of its cell's corners, the mean over the four corners p of
/// n_p · (c − p)/|c − p| being negative (the inner pole of a sample lies against its outward
/// normal: Amenta, Choi & Kolluri's pole labelling, with the normals given), and within the
/// points' bounding box (the solid's medial axis is: a nearly flat cell on the surface has its
/// circumcentre far off along the normal, on either side).
std::vector<char> inside_by_normals(const DelaunayTetrahedralization& dt, const std::vector<Vec3>& points,
                                    const std::vector<Vec3>& normals) {
  Vec3 lo = points.front(), hi = lo;
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::vector<char> inside(dt.cells.size(), 0);
  tbb::parallel_for(std::size_t{0}, dt.cells.size(), [&](std::size_t c) {
    const Vec3& centre = dt.circumcentres[c];
    if ((centre.array() < lo.array()).any() || (centre.array() > hi.array()).any()) return;
    double side = 0;
    for (const Index p : dt.cells[c]) {
      const Vec3 to_centre = dt.circumcentres[c] - points[p];
      const double length = to_centre.norm();
      if (length > 0) side += normals[p].dot(to_centre) / length;
    }
    inside[c] = side < 0;
  });
  return inside;
}

/// 3.-5. The complex of the interior cells.
MedialComplex assemble(const DelaunayTetrahedralization& dt, const std::vector<char>& inside,
                       const InteriorVoronoiOptions& options, InteriorVoronoiReport& info) {
  const auto t0 = Clock::now();
  std::vector<Node> nodes;
  MedialComplex medial;
  medial.generator_kind = options.generator_kind;
  info.interior = compact_cells(dt, inside, options.parallel, nodes, medial);
  if (options.connectivity != Connectivity::None) add_voronoi_edges(nodes, medial);
  info.voronoi_edges = medial.edges.size();
  if (options.connectivity == Connectivity::Faces) info.voronoi_faces = add_voronoi_faces(nodes, options.parallel, medial);
  info.seconds_complex = seconds_since(t0);
  return medial;
}

void record_delaunay(const DelaunayTetrahedralization& dt, InteriorVoronoiReport& info) {
  if (dt.cells.size() >= kNone)
    throw std::invalid_argument("interior Voronoi: too many Delaunay cells for 32-bit indices");
  info.points = dt.vertex_point.size();
  info.cells = dt.cells.size();
}

}  // namespace

MedialComplex interior_voronoi(const std::vector<Vec3>& points, const SurfaceMesh& mesh,
                               const InteriorVoronoiOptions& options, InteriorVoronoiReport* report) {
  if (options.inside == InsideMethod::Normals)
    throw std::invalid_argument("the normals inside test takes oriented samples: call interior_voronoi(samples)");
  InteriorVoronoiReport info;
  auto t0 = Clock::now();

  // 1. The Delaunay tetrahedralization, while the other core prepares the inside test.
  std::optional<services::RayParityInside> ray_grid;
  std::optional<services::InsideTest> side_of_mesh;
  const auto prepare_inside = [&] {
    if (options.inside == InsideMethod::RayGrid) ray_grid.emplace(mesh);
    else side_of_mesh.emplace(mesh);
  };
  const DelaunayTetrahedralization dt =
      services::delaunay_tetrahedralize_alongside(points, {options.parallel}, prepare_inside);
  record_delaunay(dt, info);
  info.seconds_delaunay = seconds_since(t0);

  // 2. Which circumcentres are strictly inside the mesh.
  t0 = Clock::now();
  const std::vector<char> inside = ray_grid ? ray_grid->inside(dt.circumcentres, options.parallel)
                                            : side_of_mesh->inside(dt.circumcentres);
  info.seconds_inside = seconds_since(t0);

  MedialComplex medial = assemble(dt, inside, options, info);
  if (report) *report = info;
  return medial;
}

MedialComplex interior_voronoi(const OrientedSamples& samples, const InteriorVoronoiOptions& options,
                               InteriorVoronoiReport* report) {
  if (samples.normals.size() != samples.size())
    throw std::invalid_argument("the samples have no normals to tell inside from outside: estimate them (`normals` "
                                "stage) or give a mesh");
  InteriorVoronoiReport info;
  auto t0 = Clock::now();
  const DelaunayTetrahedralization dt = services::delaunay_tetrahedralize(samples.points, {options.parallel});
  record_delaunay(dt, info);
  info.seconds_delaunay = seconds_since(t0);
  t0 = Clock::now();
  const std::vector<char> inside = inside_by_normals(dt, samples.points, samples.normals);
  info.seconds_inside = seconds_since(t0);
  MedialComplex medial = assemble(dt, inside, options, info);
  if (report) *report = info;
  return medial;
}

}  // namespace medax::voronoi
