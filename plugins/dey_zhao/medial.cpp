#include "medial.hpp"

#include "inner.hpp"
#include "medial_passes.hpp"

#include <medax/services/blocks.hpp>
#include <medax/services/delaunay_rings.hpp>
#include <medax/services/morton.hpp>
#include <medax/union_find.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>

namespace medax::dey_zhao {

const std::vector<std::pair<std::string, InnerSelection>>& inner_selection_names() {
  static const std::vector<std::pair<std::string, InnerSelection>> names{
      {"auto", InnerSelection::Auto},
      {"delaunay_surface", InnerSelection::DelaunaySurface},
      {"mesh", InnerSelection::Mesh},
      {"normals", InnerSelection::Normals},
      {"none", InnerSelection::None},
  };
  return names;
}

const char* to_string(InnerSelection s) {
  for (const auto& [name, value] : inner_selection_names())
    if (value == s) return name.c_str();
  return "?";
}

namespace {

using services::DelaunayTetrahedralization;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// The points' indices along a Morton (Z-order) curve of their bounding box, ties by index.
/// Computing in that order keeps the per-point arrays and the cells (sorted by corners) local in
/// memory; samples often come in random order. The codes depend on coordinates only through
/// comparisons and the ratios (x − lo) / (hi − lo), so scaling by a power of two keeps them.
std::vector<Index> spatial_order(const std::vector<Vec3>& P, bool parallel) {
  const std::size_t n = P.size();
  std::vector<Index> order(n);
  if (n == 0) return order;
  Vec3 lo = P[0], hi = P[0];
  for (const Vec3& p : P) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::vector<std::pair<std::uint64_t, Index>> keys(n);
  const auto key = [&](std::size_t i) {
    std::uint64_t cell[3];
    for (int a = 0; a < 3; ++a) {
      const double extent = hi[a] - lo[a];
      const double f = extent > 0 ? (P[i][a] - lo[a]) / extent : 0.0;
      cell[a] = static_cast<std::uint64_t>(std::min(2097151.0, std::max(0.0, std::floor(f * 2097152.0))));
    }
    keys[i] = {services::morton_code(cell[0], cell[1], cell[2]), static_cast<Index>(i)};
  };
  if (parallel) {
    tbb::parallel_for(std::size_t{0}, n, key);
    services::stable_sort_by_code(keys);
  } else {
    for (std::size_t i = 0; i < n; ++i) key(i);
    std::sort(keys.begin(), keys.end());
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].second;
  return order;
}

Renumbered renumber_points(const MedialInput& input, bool parallel) {
  Renumbered r;
  r.original = spatial_order(*input.points, parallel);
  r.P.resize(r.original.size());
  for (std::size_t i = 0; i < r.P.size(); ++i) r.P[i] = (*input.points)[r.original[i]];
  r.has_normals = input.normals && input.normals->size() == r.P.size();
  if (r.has_normals) {
    r.normals.resize(r.P.size());
    for (std::size_t i = 0; i < r.P.size(); ++i) r.normals[i] = (*input.normals)[r.original[i]];
  }
  return r;
}

/// The inner selection asked for, what it can use, and the mesh test built alongside the
/// Delaunay tetrahedralization.
struct InnerSetup {
  InnerSelection inner = InnerSelection::Auto;  ///< as requested (pass F resolves Auto)
  bool has_mesh = false;
  bool try_surface = false;   ///< DelaunaySurface may apply: tried once the cells are known
  bool prepare_mesh = false;  ///< build the mesh test alongside the tetrahedralization
  std::optional<MeshEdgeSide> mesh_side;
  std::string mesh_side_error;  ///< why the mesh test could not be built
};

/// Refuses an inner selection that lacks its data, and plans the setup of the one that can run.
InnerSetup plan_inner(const MedialInput& input, const Renumbered& points, InnerSelection inner) {
  InnerSetup s;
  s.inner = inner;
  s.has_mesh = input.mesh && !input.mesh->faces.empty();
  if (inner == InnerSelection::DelaunaySurface && !(s.has_mesh && input.points_are_mesh_vertices))
    throw std::invalid_argument("inner selection `delaunay_surface` needs the mesh, with the points being its "
                                "vertices (`points: vertices`)");
  if (inner == InnerSelection::Mesh && !s.has_mesh)
    throw std::invalid_argument("inner selection `mesh` needs a surface mesh");
  if (inner == InnerSelection::Normals && !points.has_normals)
    throw std::invalid_argument("inner selection `normals` needs one outward normal per point");
  s.try_surface = (inner == InnerSelection::Auto || inner == InnerSelection::DelaunaySurface) && s.has_mesh &&
                  input.points_are_mesh_vertices;
  s.prepare_mesh = inner == InnerSelection::Mesh || (inner == InnerSelection::Auto && s.has_mesh && !s.try_surface);
  return s;
}

/// Builds the mesh test when planned (an open mesh is refused under Mesh, noted under Auto).
void prepare_mesh_side(const MedialInput& input, InnerSetup& s) {
  if (!s.prepare_mesh) return;
  try {
    s.mesh_side.emplace(*input.mesh);
  } catch (const std::invalid_argument& e) {
    if (s.inner == InnerSelection::Mesh) throw;
    s.mesh_side_error = e.what();
  }
}

/// A. The Delaunay tetrahedralization and its circumcentres, the mesh test built alongside.
DelaunayTetrahedralization tetrahedralize(const Renumbered& points, const MedialInput& input, bool parallel,
                                          InnerSetup& inner, MedialReport& info) {
  DelaunayTetrahedralization dt = services::delaunay_tetrahedralize_alongside(
      points.P, {parallel}, [&] { prepare_mesh_side(input, inner); });
  const std::size_t n = dt.cells.size();
  if (n >= kNone / 4) throw std::invalid_argument("too many Delaunay cells for 32-bit indices");
  info.points = dt.vertex_point.size();
  info.cells = n;
  return dt;
}

/// After B–C: the points on the hull, the empty umbrellas and the number of Delaunay edges.
void count_umbrellas(const DelaunayTetrahedralization& dt, const Umbrellas& u, MedialReport& info) {
  const std::size_t n = dt.cells.size();
  std::size_t hull_facets = 0;
  for (const auto& nb : dt.neighbours)
    for (std::int64_t x : nb) hull_facets += x == kInf;
  for (Index x : dt.vertex_point) {
    info.hull_points += u.on_hull[x] != 0;
    info.empty_umbrellas += u.size(x) == 0;
  }
  // Euler: V − E + F − C = 1 for a triangulated ball, with F = (4C + H) / 2.
  info.delaunay_edges = info.points + (4 * n + hull_facets) / 2 - n - 1;
}

/// The mesh triangles in the renumbered point indices (indices past the points left as they are).
SurfaceMesh renumber_mesh(const SurfaceMesh& mesh, const std::vector<Index>& original) {
  const std::size_t np = original.size();
  std::vector<Index> position(np);
  for (std::size_t i = 0; i < np; ++i) position[original[i]] = static_cast<Index>(i);
  const auto at = [&](Index v) { return v < np ? position[v] : v; };
  SurfaceMesh renumbered;
  renumbered.faces.reserve(mesh.faces.size());
  for (const Tri& f : mesh.faces) renumbered.faces.push_back({at(f[0]), at(f[1]), at(f[2])});
  return renumbered;
}

/// F (a): labels the cells inside (1) by the mesh triangles when they are all Delaunay facets.
/// When they are not, DelaunaySurface is refused, and Auto notes why and builds the mesh test.
bool label_cells(const Renumbered& points, const MedialInput& input, const DelaunayTetrahedralization& dt,
                 InnerSetup& setup, std::vector<char>& cell_inside, MedialReport& info) {
  std::size_t missing = 0;
  bool labelled = false;
  try {
    labelled = label_cells_by_surface(dt, renumber_mesh(*input.mesh, points.original), cell_inside, missing);
  } catch (const std::invalid_argument&) {
    if (setup.inner == InnerSelection::DelaunaySurface) throw;
    info.inner_note = "the mesh triangles are Delaunay facets but their inside parity is inconsistent; ";
  }
  if (labelled) {
    info.inner_note += "every mesh triangle is a Delaunay facet";
    return true;
  }
  if (setup.inner == InnerSelection::DelaunaySurface)
    throw std::invalid_argument("inner selection `delaunay_surface`: " + std::to_string(missing) + " of " +
                                std::to_string(input.mesh->faces.size()) +
                                " mesh triangles are not Delaunay facets of the points; use `inner: mesh`");
  if (missing) info.inner_note += std::to_string(missing) + " mesh triangles are not Delaunay facets; ";
  try {
    setup.mesh_side.emplace(*input.mesh);
  } catch (const std::invalid_argument& e) {
    setup.mesh_side_error = e.what();
  }
  return false;
}

/// F, `auto` without Delaunay mesh triangles: the mesh test when the mesh is closed, else the
/// normals, else none.
InnerSelection choose_inner(const InnerSetup& setup, bool has_normals, MedialReport& info) {
  if (setup.mesh_side) {
    info.inner_note += "general closed mesh";
    return InnerSelection::Mesh;
  }
  const std::string unusable = setup.has_mesh ? "mesh unusable (" + setup.mesh_side_error + "); " : std::string();
  if (has_normals) {
    info.inner_note += unusable + "oriented normals";
    return InnerSelection::Normals;
  }
  info.inner_note += unusable + "no mesh and no normals: inner and outer medial axis";
  return InnerSelection::None;
}

/// Whether every Voronoi vertex of the facet dual to `s` lies within the points' bounding box
/// [lo, hi]: the inner medial axis does, while a nearly flat cell on the surface has its
/// circumcentre far off along the normal, on either side (Normals has no mesh to reject it).
bool facet_in_box(const Selected& s, const Selection& selection, const DelaunayTetrahedralization& dt,
                  const Vec3& lo, const Vec3& hi) {
  for (std::uint32_t k = 0; k < s.ring_size; ++k) {
    const Vec3& c = dt.circumcentres[selection.rings[s.ring_begin + k]];
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) return false;
  }
  return true;
}

/// F: 1 for each selected edge that `inner` keeps.
std::vector<char> keep_inner(InnerSelection inner, const Renumbered& points, const Selection& selection,
                             const std::vector<char>& cell_inside, const InnerSetup& setup,
                             const DelaunayTetrahedralization& dt, bool parallel) {
  const std::vector<Vec3>& P = points.P;
  const FreshArray<Selected>& selected = selection.selected;
  std::vector<char> keep(selected.size(), 1);
  switch (inner) {
    case InnerSelection::DelaunaySurface:
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        bool all = !s.open;
        for (std::uint32_t k = 0; k < s.ring_size && all; ++k)
          all = cell_inside[selection.rings[s.ring_begin + k]] != 0;
        keep[i] = all;
      }
      break;
    case InnerSelection::Mesh: {
      std::vector<std::array<Index, 2>> edges(selected.size());
      for (std::size_t i = 0; i < selected.size(); ++i) edges[i] = {selected[i].p, selected[i].q};
      keep = setup.mesh_side->inner(P, edges, parallel);
      break;
    }
    case InnerSelection::Normals: {
      const auto& N = points.normals;
      Vec3 lo = P[dt.vertex_point[0]], hi = lo;
      for (Index x : dt.vertex_point) lo = lo.cwiseMin(P[x]), hi = hi.cwiseMax(P[x]);
      for (std::size_t i = 0; i < selected.size(); ++i) {
        const Selected& s = selected[i];
        const Vec3 d = P[s.q] - P[s.p];
        keep[i] = N[s.p].dot(d) < 0 && N[s.q].dot(d) > 0 && facet_in_box(s, selection, dt, lo, hi);
      }
      break;
    }
    default: break;
  }
  return keep;
}

/// F. Inner/outer selection: which selected facets are kept; the report says which selection
/// ran, why, and how many it rejected.
std::vector<char> select_inner(const Renumbered& points, const MedialInput& input, const DelaunayTetrahedralization& dt,
                               const Selection& selection, InnerSetup& setup, bool parallel, MedialReport& info) {
  InnerSelection inner = setup.inner;
  std::vector<char> cell_inside;
  if (setup.try_surface && label_cells(points, input, dt, setup, cell_inside, info))
    inner = InnerSelection::DelaunaySurface;
  if (inner == InnerSelection::Auto) inner = choose_inner(setup, points.has_normals, info);
  info.inner_used = inner;
  std::vector<char> keep = keep_inner(inner, points, selection, cell_inside, setup, dt, parallel);
  for (char k : keep) info.outer += !k;
  return keep;
}

}  // namespace

MedialComplex medial_axis(const MedialInput& input, const MedialOptions& options, MedialReport* report) {
  if (!input.points) throw std::invalid_argument("no points");
  MedialReport info;
  auto t0 = Clock::now();
  const Renumbered points = renumber_points(input, options.parallel);
  InnerSetup inner = plan_inner(input, points, options.inner);

  // A. The Delaunay tetrahedralization (the inner test's setup alongside).
  const DelaunayTetrahedralization dt = tetrahedralize(points, input, options.parallel, inner, info);
  info.seconds_delaunay = seconds_since(t0);

  // B–C. Poles and umbrellas.
  t0 = Clock::now();
  const Umbrellas u = compute_umbrellas(points.P, dt, false, options.parallel);
  count_umbrellas(dt, u, info);
  info.seconds_umbrellas = seconds_since(t0);

  // D–E. The conditions on every edge; rings of the selected.
  t0 = Clock::now();
  const Selection selection = select_edges(points, dt, u, options, info);
  info.seconds_filter = seconds_since(t0);

  // F. Inner/outer selection.
  t0 = Clock::now();
  const std::vector<char> keep = select_inner(points, input, dt, selection, inner, options.parallel, info);
  info.seconds_inner = seconds_since(t0);

  // The output complex.
  t0 = Clock::now();
  MedialComplex medial = build_complex(points, dt, selection, keep, options, info);
  info.seconds_complex = seconds_since(t0);
  if (report) *report = info;
  return medial;
}

}  // namespace medax::dey_zhao
