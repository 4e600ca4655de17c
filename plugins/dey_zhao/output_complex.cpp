// MEDIAL's output: the kept Voronoi facets with shared vertices (close circumcentres merged),
// fan-triangulated, their closure's edges, and the labels and fields of every element.
#include "medial_passes.hpp"

#include <medax/services/blocks.hpp>
#include <medax/union_find.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>

namespace medax::dey_zhao {

using services::DelaunayTetrahedralization;

namespace {

/// Diagonal of the bounding box of the points in the tetrahedralization.
double bbox_diagonal(const std::vector<Vec3>& P, const DelaunayTetrahedralization& dt) {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (!P.empty())
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = P[dt.vertex_point[0]][a];
  for (Index x : dt.vertex_point)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], P[x][a]), hi[a] = std::max(hi[a], P[x][a]);
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// What the kept facets' rings give: the cells used as facet vertices, and the consecutive
/// facet vertices closer than the tolerance (cospherical points: many cells, one circumcentre).
struct RingScan {
  std::size_t cells = 0;
  std::unique_ptr<std::atomic<std::uint8_t>[]> used;  ///< per cell: 1 when around a kept facet
  std::vector<std::array<Index, 2>> close;  ///< in facet order
};

/// One pass over the kept facets' rings, in parallel blocks (close pairs gathered in block order).
RingScan scan_rings(const Selection& selection, const std::vector<char>& keep, const DelaunayTetrahedralization& dt,
                    double tolerance, bool parallel) {
  const auto& cc = dt.circumcentres;
  RingScan out;
  out.cells = dt.cells.size();
  out.used = std::make_unique<std::atomic<std::uint8_t>[]>(out.cells);  // zeros
  const std::size_t m = selection.selected.size();
  std::vector<std::vector<std::array<Index, 2>>> close(services::block_count(m, kBlock));
  services::for_blocks(m, kBlock, parallel, [&](std::size_t block, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (!keep[i]) continue;
      const Selected& s = selection.selected[i];
      const Index* r = selection.rings.data() + s.ring_begin;
      for (std::uint32_t k = 0; k < s.ring_size; ++k) {
        out.used[r[k]].store(1, std::memory_order_relaxed);
        if (s.open && k + 1 == s.ring_size) break;  // no Voronoi edge between the chain's two ends
        const Index a = r[k], b = r[(k + 1) % s.ring_size];
        if (a != b && (cc[a] - cc[b]).norm() <= tolerance) close[block].push_back({a, b});
      }
    }
  });
  for (const auto& pairs : close) out.close.insert(out.close.end(), pairs.begin(), pairs.end());
  return out;
}

/// The merge classes of the close pairs, each represented by its lowest cell (UnionFind's rule:
/// independent of the order of unions). Empty when nothing merges.
std::optional<UnionFind> merge_close_cells(const RingScan& scan) {
  std::optional<UnionFind> classes;
  if (scan.close.empty()) return classes;
  classes.emplace(scan.cells);
  for (const auto& [a, b] : scan.close) classes->unite(a, b);
  return classes;
}

/// The output vertices of the cells.
struct CellVertices {
  FreshArray<Index> of_cell;  ///< per cell: its vertex (a merged cell: its class's), kNone if unused
  FreshArray<Index> cell;     ///< per vertex: its cell
};

/// Vertex numbering: the used cells in cell order, each merge class numbered once (by its
/// lowest cell, one of the used cells, which stands for the others). Blocks count their cells,
/// then number them from their offsets, in parallel (the arrays' first touch).
CellVertices number_cells(RingScan& scan, std::optional<UnionFind>& classes, bool parallel, MedialReport& info) {
  const std::size_t n = scan.cells;
  const auto used = [&](std::size_t c) { return scan.used[c].load(std::memory_order_relaxed) != 0; };
  std::vector<Index> merged;
  if (classes)
    for (std::size_t c = 0; c < n; ++c)
      if (used(c) && classes->find(static_cast<Index>(c)) != c) {
        scan.used[c].store(0, std::memory_order_relaxed);
        merged.push_back(static_cast<Index>(c));
      }
  info.merged_vertices += merged.size();
  std::vector<std::size_t> offset(services::block_count(n, kBlock) + 1, 0);
  services::for_blocks(n, kBlock, parallel, [&](std::size_t block, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) offset[block + 1] += used(c);
  });
  for (std::size_t b = 0; b + 1 < offset.size(); ++b) offset[b + 1] += offset[b];
  CellVertices out{FreshArray<Index>(n), FreshArray<Index>(offset.back())};
  services::for_blocks(n, kBlock, parallel, [&](std::size_t block, std::size_t begin, std::size_t end) {
    auto v = static_cast<Index>(offset[block]);
    for (std::size_t c = begin; c < end; ++c) {
      out.of_cell.construct(c, used(c) ? v : kNone);
      if (used(c)) out.cell.construct(v++, static_cast<Index>(c));
    }
  });
  for (Index c : merged) out.of_cell.construct(c, out.of_cell[classes->find(c)]);
  return out;
}

/// Runs every job, in parallel or in order.
void run_all(const std::vector<std::function<void()>>& jobs, bool parallel) {
  services::for_blocks(jobs.size(), 1, parallel, [&](std::size_t, std::size_t job, std::size_t) { jobs[job](); });
}

/// The vertices of the used cells: circumcentre, circumradius (the Delaunay ball), generators =
/// the cell's 4 corners (sorted). The complex has no vertex column yet: its vectors are filled
/// in place, in parallel.
void add_cell_vertices(MedialComplex& medial, const CellVertices& cells, const DelaunayTetrahedralization& dt,
                       const std::vector<Index>& original, bool parallel) {
  const std::size_t nv = cells.cell.size();
  run_all({[&] { medial.centres.resize(nv); }, [&] { medial.radii.resize(nv); },
           [&] { medial.generators.resize(nv); }},
          parallel);
  services::for_blocks(nv, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Index c = cells.cell[v];
      medial.centres[v] = dt.circumcentres[c];
      medial.radii[v] = dt.circumradii[c];
      std::array<Index, 4> g;
      for (int k = 0; k < 4; ++k) g[k] = original[dt.cells[c][k]];
      std::sort(g.begin(), g.end());
      medial.generators[v].assign(g.begin(), g.end());
    }
  });
}

/// The clipped ray ends (Unbounded::Clip): their vertices follow the cells' vertices.
struct RayVertices {
  std::vector<std::int64_t> rays;  ///< hull facets (cell·4 + k) of the kept rays, sorted, each once
  Index first = 0;                 ///< the vertex of rays[0]

  Index of(std::int64_t ray) const {
    return first + static_cast<Index>(std::lower_bound(rays.begin(), rays.end(), ray) - rays.begin());
  }
  bool is_ray(Index vertex) const { return vertex >= first; }
};

/// Adds a vertex at each kept ray's end, clip_factor bounding-box diagonals from its
/// circumcentre along the hull facet's normal; generators = the hull facet's 3 corners.
RayVertices add_ray_vertices(MedialComplex& medial, const Selection& selection, const std::vector<char>& keep,
                             const DelaunayTetrahedralization& dt, const Renumbered& points, double ray_length) {
  RayVertices out;
  for (std::size_t i = 0; i < selection.selected.size(); ++i) {
    const Selected& s = selection.selected[i];
    if (keep[i] && s.open) out.rays.push_back(s.first_ray), out.rays.push_back(s.last_ray);
  }
  std::sort(out.rays.begin(), out.rays.end());
  out.rays.erase(std::unique(out.rays.begin(), out.rays.end()), out.rays.end());
  out.first = static_cast<Index>(medial.num_vertices());
  for (std::int64_t ray : out.rays) {
    const Index c = static_cast<Index>(ray / 4);
    const int k = static_cast<int>(ray % 4);
    const auto f = facet_corners(dt.cells[c], k);
    const Vec3 end = dt.circumcentres[c] + ray_length * unit(outward_normal(points.P, dt.cells[c], k));
    const Index v = medial.add_vertex(end, (end - points.P[f[0]]).norm());
    std::array<Index, 3> g{points.original[f[0]], points.original[f[1]], points.original[f[2]]};
    std::sort(g.begin(), g.end());
    medial.generators[v].assign(g.begin(), g.end());
  }
  return out;
}

/// An edge of the closure, before sorting and deduplication.
struct EdgeRecord {
  Index a, b;
  int diagonal, clipped;
  bool operator<(const EdgeRecord& o) const {
    return a != o.a ? a < o.a : b != o.b ? b < o.b : diagonal != o.diagonal ? diagonal < o.diagonal : clipped > o.clipped;
  }
};

/// The closure's edge records bucketed by their lower vertex a: bucket v is
/// records[start[v], start[v + 1]). Scattered in parallel through per-vertex cursors, so a
/// bucket's order is unspecified; add_edges sorts it by EdgeRecord's order, a total order on
/// every field, which makes the result independent of it.
struct EdgeBuckets {
  std::vector<std::size_t> start;
  std::unique_ptr<std::atomic<std::size_t>[]> cursor;  ///< per vertex: its edge count, then its next slot
  std::unique_ptr<EdgeRecord[]> records;  ///< not zero-filled: the scatter's writes are its first touch
};

/// What the kept facets of one block add: their facets (collapsed ones too) and triangles.
struct BlockCount {
  std::size_t faces = 0;
  int facets = 0, degenerate = 0;
};

/// What the passes over the kept facets read.
struct KeptFacets {
  const Selection& selection;
  const FreshArray<Index>& cell_vertex;
  const RayVertices& rays;
  std::vector<std::uint32_t> index;  ///< the kept facets' positions in selection.selected
};

/// The vertex cycle of a kept facet around p → q: its cells' vertices (consecutive repeats after
/// merging dropped), between its two ray ends when it is open.
void facet_cycle(const Selected& s, const Index* ring, const FreshArray<Index>& cell_vertex, const RayVertices& rays,
                 std::vector<Index>& cycle) {
  cycle.clear();
  if (s.open) cycle.push_back(rays.of(s.first_ray));
  for (std::uint32_t k = 0; k < s.ring_size; ++k) {
    const Index vtx = cell_vertex[ring[k]];
    if (cycle.empty() || cycle.back() != vtx) cycle.push_back(vtx);
  }
  if (s.open) cycle.push_back(rays.of(s.last_ray));
  while (cycle.size() > 1 && cycle.back() == cycle.front()) cycle.pop_back();
}

/// visit(block, facet, cycle) for every kept facet, in fixed blocks of kept facets (in order
/// within a block; blocks in parallel).
template <typename Visit>
void for_kept_cycles(const KeptFacets& kept, bool parallel, const Visit& visit) {
  services::for_blocks(kept.index.size(), kBlock, parallel, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::vector<Index> cycle;
    for (std::size_t j = begin; j < end; ++j) {
      const Selected& s = kept.selection.selected[kept.index[j]];
      facet_cycle(s, kept.selection.rings.data() + s.ring_begin, kept.cell_vertex, kept.rays, cycle);
      visit(b, s, cycle);
    }
  });
}

/// A facet's boundary edges, then its fan triangles from the first vertex with their diagonals:
/// edge(record) and face(triangle) in that order. A facet collapsed to a point or a segment is
/// kept in the closure only: returns false.
template <typename Edge, typename Face>
bool emit_facet(const std::vector<Index>& cycle, const RayVertices& rays, const Edge& edge, const Face& face) {
  const std::size_t m = cycle.size();
  for (std::size_t k = 0; k < m && m > 1; ++k) {
    const Index a = cycle[k], c = cycle[(k + 1) % m];
    if (m == 2 && k == 1) break;  // a segment: one edge
    if (a != c) edge(EdgeRecord{std::min(a, c), std::max(a, c), 0, rays.is_ray(a) || rays.is_ray(c)});
  }
  if (m < 3) return false;
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const Index a = cycle[0], b2 = cycle[k], c = cycle[k + 1];
    if (k >= 2 && a != b2) edge(EdgeRecord{std::min(a, b2), std::max(a, b2), 1, rays.is_ray(a) || rays.is_ray(b2)});
    if (a == b2 || b2 == c || a == c) continue;  // a non-consecutive repeat after merging
    face(Tri{a, b2, c});
  }
  return true;
}

/// First pass: each block's facets and triangles, and each vertex's edge records (its cursor).
std::vector<BlockCount> count_facets(const KeptFacets& kept, EdgeBuckets& buckets, bool parallel) {
  std::vector<BlockCount> counts(services::block_count(kept.index.size(), kBlock));
  for_kept_cycles(kept, parallel, [&](std::size_t b, const Selected&, const std::vector<Index>& cycle) {
    BlockCount& count = counts[b];
    ++count.facets;
    const auto edge = [&](const EdgeRecord& e) { buckets.cursor[e.a].fetch_add(1, std::memory_order_relaxed); };
    if (!emit_facet(cycle, kept.rays, edge, [&](const Tri&) { ++count.faces; })) ++count.degenerate;
  });
  return counts;
}

/// The buckets' starts from the counts; each cursor set to its bucket's start.
void open_buckets(EdgeBuckets& buckets, std::size_t nv) {
  buckets.start.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    const std::size_t count = buckets.cursor[v].load(std::memory_order_relaxed);
    buckets.start[v + 1] = buckets.start[v] + count;
    buckets.cursor[v].store(buckets.start[v], std::memory_order_relaxed);
  }
  buckets.records.reset(new EdgeRecord[buckets.start[nv]]);  // default-initialised: not zero-filled
}

/// Where a block's triangles and facet numbers start (the blocks in order).
struct BlockStart {
  std::size_t face = 0;
  int facet = 0;
};

/// The triangles with their face labels and fields, at their final rows.
struct FaceColumns {
  std::vector<Tri>& faces;
  std::vector<int>&polygon, &p, &q, &conditions, &unbounded;
  std::vector<double>&angle, &ratio;
};

/// Second pass: each block's triangles and labels written from its start (the complex's face
/// order is the blocks' order), its edge records scattered into their buckets.
void write_facets(const KeptFacets& kept, std::vector<BlockStart> next, const std::vector<Index>& original,
                  FaceColumns out, EdgeBuckets& buckets, bool parallel) {
  for_kept_cycles(kept, parallel, [&](std::size_t b, const Selected& s, const std::vector<Index>& cycle) {
    BlockStart& at = next[b];
    const int number = at.facet++;
    const double angle = std::asin(std::clamp(std::max(s.scores.sin_angle_p, s.scores.sin_angle_q), 0.0, 1.0));
    const double ratio = std::max(s.scores.ratio_p, s.scores.ratio_q);
    const auto edge = [&](const EdgeRecord& e) {
      buckets.records[buckets.cursor[e.a].fetch_add(1, std::memory_order_relaxed)] = e;
    };
    emit_facet(cycle, kept.rays, edge, [&](const Tri& t) {
      const std::size_t i = at.face++;
      out.faces[i] = t;
      out.polygon[i] = number;
      out.p[i] = static_cast<int>(original[s.p]);
      out.q[i] = static_cast<int>(original[s.q]);
      out.conditions[i] = s.bits;
      out.unbounded[i] = s.open ? 1 : 0;
      out.angle[i] = angle;
      out.ratio[i] = ratio;
    });
  });
}

/// The kept facets, fan-triangulated, into the complex (in blocks of kept facets, in order; facet
/// numbers global), with their face labels and fields; returns their closure's edge records,
/// bucketed. Two passes (count, then write at the counted rows): no per-block copies.
EdgeBuckets add_facets(MedialComplex& medial, const KeptFacets& kept, const std::vector<Index>& original,
                       bool parallel, MedialReport& info) {
  EdgeBuckets buckets;
  buckets.cursor = std::make_unique<std::atomic<std::size_t>[]>(medial.num_vertices());  // zeros
  const std::vector<BlockCount> counts = count_facets(kept, buckets, parallel);
  open_buckets(buckets, medial.num_vertices());
  std::vector<BlockStart> starts(counts.size() + 1);
  for (std::size_t b = 0; b < counts.size(); ++b) {
    starts[b + 1] = {starts[b].face + counts[b].faces, starts[b].facet + counts[b].facets};
    info.degenerate_facets += static_cast<std::size_t>(counts[b].degenerate);
  }
  info.facets = static_cast<std::size_t>(starts.back().facet);
  // The columns while there are no faces (empty), then the faces and every column sized at once
  // (add_face would grow each column per face, and zero-filling them one after the other took one
  // thread through 190 MB at 1M).
  FaceColumns columns{medial.faces,        medial.add(kPolygon),   medial.add(kDualP),
                      medial.add(kDualQ),  medial.add(kConditions), medial.add(kUnbounded),
                      medial.add(kAngle),  medial.add(kRatio)};
  const std::size_t faces = starts.back().face;
  run_all({[&] { columns.faces.resize(faces); }, [&] { columns.polygon.resize(faces); },
           [&] { columns.p.resize(faces); }, [&] { columns.q.resize(faces); },
           [&] { columns.conditions.resize(faces); }, [&] { columns.unbounded.resize(faces); },
           [&] { columns.angle.resize(faces); }, [&] { columns.ratio.resize(faces); }},
          parallel);
  write_facets(kept, std::move(starts), original, columns, buckets, parallel);
  return buckets;
}

/// The closure's edges into the complex, sorted by (a, b), each once (a Voronoi edge bounds up
/// to three selected facets; the first record of an (a, b) in EdgeRecord's order is kept), with
/// their labels `fan_diagonal` and, when clipping, `clipped`: each (short) bucket sorted and
/// deduplicated, then written at its offset, in parallel.
void add_edges(MedialComplex& medial, EdgeBuckets& buckets, bool clip, bool parallel) {
  const std::size_t nv = medial.num_vertices();
  const std::vector<std::size_t>& start = buckets.start;
  EdgeRecord* const records = buckets.records.get();
  std::vector<std::size_t> kept(nv + 1, 0);  // then: the offset of each bucket's edges
  services::for_blocks(nv, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      EdgeRecord* const first = records + start[v];
      EdgeRecord* const last = records + start[v + 1];
      std::sort(first, last);
      kept[v + 1] = static_cast<std::size_t>(
          std::unique(first, last, [](const EdgeRecord& x, const EdgeRecord& y) { return x.b == y.b; }) - first);
    }
  });
  for (std::size_t v = 0; v < nv; ++v) kept[v + 1] += kept[v];
  // The columns while there are no edges, then all sized at once (as the faces').
  auto& fan_diagonal = medial.add(kFanDiagonal);
  std::vector<int>* clipped = clip ? &medial.add(kClipped) : nullptr;
  const std::size_t edges = kept[nv];
  run_all({[&] { medial.edges.resize(edges); }, [&] { fan_diagonal.resize(edges); },
           [&] {
             if (clipped) clipped->resize(edges);
           }},
          parallel);
  services::for_blocks(nv, kBlock, parallel, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      for (std::size_t i = kept[v], k = start[v]; i < kept[v + 1]; ++i, ++k) {
        medial.edges[i] = {records[k].a, records[k].b};
        fan_diagonal[i] = records[k].diagonal;
        if (clipped) (*clipped)[i] = records[k].clipped;
      }
  });
}

}  // namespace

MedialComplex build_complex(const Renumbered& points, const DelaunayTetrahedralization& dt, const Selection& selection,
                            const std::vector<char>& keep, const MedialOptions& options, MedialReport& info) {
  const double diagonal = bbox_diagonal(points.P, dt);
  RingScan scan = scan_rings(selection, keep, dt, options.merge_tolerance * diagonal, options.parallel);
  std::optional<UnionFind> classes = merge_close_cells(scan);
  const CellVertices cells = number_cells(scan, classes, options.parallel, info);
  MedialComplex medial;
  medial.generator_kind = options.generator_kind;
  add_cell_vertices(medial, cells, dt, points.original, options.parallel);
  const RayVertices rays = add_ray_vertices(medial, selection, keep, dt, points, options.clip_factor * diagonal);
  KeptFacets kept{selection, cells.of_cell, rays, {}};
  for (std::size_t i = 0; i < selection.selected.size(); ++i)
    if (keep[i]) kept.index.push_back(static_cast<std::uint32_t>(i));
  EdgeBuckets edges = add_facets(medial, kept, points.original, options.parallel, info);
  add_edges(medial, edges, options.unbounded == Unbounded::Clip, options.parallel);
  return medial;
}

}  // namespace medax::dey_zhao
