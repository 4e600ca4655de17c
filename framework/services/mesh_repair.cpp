// Mesh repair with CGAL Polygon_mesh_processing: soup clean-up and orientation, degenerate-face
// removal, hole filling, self-intersection removal; the result is always checked again.
#include <medax/services/mesh_check.hpp>

#include "cgal_mesh.hpp"
#include "plural.hpp"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED  // fairing needs CGAL's Eigen sparse solver; Eigen is a kernel dependency
#endif

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace medax::services {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::CgalMesh;
using detail::Point;
using Polygon = std::vector<std::size_t>;
using face_descriptor = CgalMesh::Face_index;
using vertex_descriptor = CgalMesh::Vertex_index;
using halfedge_descriptor = CgalMesh::Halfedge_index;

using detail::plural;

SurfaceMesh to_surface(const CgalMesh& in) {
  SurfaceMesh out;
  std::vector<Index> index(in.number_of_vertices() + in.number_of_removed_vertices(), 0);
  for (vertex_descriptor v : in.vertices()) {
    index[v] = static_cast<Index>(out.vertices.size());
    out.vertices.push_back(detail::to_vec(in.point(v)));
  }
  for (face_descriptor f : in.faces()) {
    Tri t{};
    int k = 0;
    for (vertex_descriptor v : CGAL::vertices_around_face(in.halfedge(f), in)) {
      if (k < 3) t[k] = index[v];
      ++k;
    }
    if (k == 3) out.faces.push_back(t);
  }
  return out;
}

/// Drops unused vertices and renumbers (soup form).
SurfaceMesh soup_to_surface(const std::vector<Point>& points, const std::vector<Polygon>& polygons) {
  SurfaceMesh out;
  std::vector<std::int64_t> index(points.size(), -1);
  for (const Polygon& p : polygons) {
    if (p.size() != 3) continue;
    Tri t{};
    for (int k = 0; k < 3; ++k) {
      if (index[p[k]] < 0) {
        index[p[k]] = static_cast<std::int64_t>(out.vertices.size());
        out.vertices.push_back(detail::to_vec(points[p[k]]));
      }
      t[k] = static_cast<Index>(index[p[k]]);
    }
    out.faces.push_back(t);
  }
  return out;
}

bool same_mesh(const SurfaceMesh& a, const SurfaceMesh& b) { return a.vertices == b.vertices && a.faces == b.faces; }

/// Orients every closed component outward: with orient_to_bound_a_volume (nesting-aware: a cavity
/// faces inward) when the mesh is closed and free of self-intersections, else component by
/// component by the sign of its volume (in coordinates scaled to the bounding box, so that the
/// sign survives extreme coordinate scales).
void orient_outward(CgalMesh& mesh, RepairResult& result) {
  if (mesh.is_empty()) return;
  auto component = mesh.add_property_map<face_descriptor, std::size_t>("f:medax_component", 0).first;
  const std::size_t count = PMP::connected_components(mesh, component);
  if (count > 1 && CGAL::is_closed(mesh) && !PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(mesh)) {
    mesh.remove_property_map(component);
    const std::vector<Tri> old_faces = to_surface(mesh).faces;
    PMP::orient_to_bound_a_volume(mesh);
    if (to_surface(mesh).faces != old_faces)
      result.actions.push_back("oriented the components to bound a volume (CGAL orient_to_bound_a_volume)");
    return;
  }
  CGAL::Bbox_3 box;
  for (vertex_descriptor v : mesh.vertices()) box += mesh.point(v).bbox();
  const Vec3 centre(0.5 * (box.xmin() + box.xmax()), 0.5 * (box.ymin() + box.ymax()), 0.5 * (box.zmin() + box.zmax()));
  const double side = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  const double size = side > 0 && std::isfinite(side) ? side : 1.0;
  const auto unit = [&](Point p) { return Vec3((detail::to_vec(p) - centre) / size); };
  std::vector<double> six_volume(count, 0.0);
  for (face_descriptor f : mesh.faces()) {
    const halfedge_descriptor h = mesh.halfedge(f);
    const Vec3 a = unit(mesh.point(mesh.source(h)));
    const Vec3 b = unit(mesh.point(mesh.target(h)));
    const Vec3 c = unit(mesh.point(mesh.target(mesh.next(h))));
    six_volume[component[f]] += a.dot(b.cross(c));
  }
  std::vector<face_descriptor> flip;
  for (face_descriptor f : mesh.faces())
    if (six_volume[component[f]] < 0) flip.push_back(f);
  mesh.remove_property_map(component);
  if (!flip.empty()) {
    PMP::reverse_face_orientations(flip, mesh);
    result.actions.push_back(fmt::format("flipped {} (components with negative volume)", plural(flip.size(), "inward face", "inward faces")));
  }
}

void fill_holes(CgalMesh& mesh, const RepairOptions& options, RepairResult& result) {
  std::vector<halfedge_descriptor> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  std::size_t filled = 0, new_faces = 0;
  for (halfedge_descriptor h : borders) {
    if (!mesh.is_border(h)) continue;  // already closed by an earlier fill
    std::size_t edges = 0;
    for ([[maybe_unused]] halfedge_descriptor g : CGAL::halfedges_around_face(h, mesh)) ++edges;
    if (options.max_hole_edges > 0 && edges > options.max_hole_edges) {
      result.failures.push_back(fmt::format("left a hole of {} edges open (max_hole_edges is {})", edges,
                                            options.max_hole_edges));
      continue;
    }
    std::vector<face_descriptor> faces;
    std::vector<vertex_descriptor> vertices;
    bool faired = true;
    if (options.fair_holes) {
      faired = std::get<0>(
          PMP::triangulate_refine_and_fair_hole(mesh, h, std::back_inserter(faces), std::back_inserter(vertices)));
    } else {
      PMP::triangulate_and_refine_hole(mesh, h, std::back_inserter(faces), std::back_inserter(vertices));
    }
    if (faces.empty()) {
      result.failures.push_back(fmt::format("could not triangulate a hole of {} edges (CGAL triangulate_hole)", edges));
      continue;
    }
    ++filled;
    new_faces += faces.size();
    if (!faired) result.failures.push_back(fmt::format("fairing failed on a hole of {} edges (left flat)", edges));
  }
  if (filled > 0)
    result.actions.push_back(fmt::format("filled {} with {} (CGAL triangulate_{}_hole)", plural(filled, "hole", "holes"),
                                         plural(new_faces, "face", "faces"),
                                         options.fair_holes ? "refine_and_fair" : "and_refine"));
}

/// Size measures used to reject a "repair" that throws away part of the shape (CGAL's
/// autorefinement can drop whole patches when its stitching fails, and still report success).
struct Measures {
  double area = 0, volume = 0, diagonal = 0;
  std::size_t components = 0;
};

Measures measure(CgalMesh& mesh) {
  Measures m;
  if (mesh.is_empty()) return m;
  auto component = mesh.add_property_map<face_descriptor, std::size_t>("f:medax_measure", 0).first;
  m.components = PMP::connected_components(mesh, component);
  mesh.remove_property_map(component);
  CGAL::Bbox_3 box;
  for (vertex_descriptor v : mesh.vertices()) box += mesh.point(v).bbox();
  m.diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                         CGAL::square(box.zmax() - box.zmin()));
  for (face_descriptor f : mesh.faces()) {
    const halfedge_descriptor h = mesh.halfedge(f);
    const Vec3 a = detail::to_vec(mesh.point(mesh.source(h)));
    const Vec3 b = detail::to_vec(mesh.point(mesh.target(h)));
    const Vec3 c = detail::to_vec(mesh.point(mesh.target(mesh.next(h))));
    m.area += 0.5 * (b - a).cross(c - a).norm();
    m.volume += a.dot(b.cross(c)) / 6.0;
  }
  m.volume = std::abs(m.volume);
  return m;
}

/// Empty when `after` keeps the shape of `before` (no more components, bounding-box diagonal
/// within 2 %, area and volume within 25 %), else why not.
std::string shape_change(const Measures& before, const Measures& after) {
  const auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(a), 1e-300); };
  if (after.components > before.components)
    return fmt::format("it split the surface into {} components (there were {})", after.components,
                       before.components);
  if (relative(before.diagonal, after.diagonal) > 0.02 || relative(before.area, after.area) > 0.25 ||
      relative(before.volume, after.volume) > 0.25)
    return fmt::format("it changed the shape too much (bounding-box diagonal {:g} -> {:g}, area {:g} -> {:g}, volume {:g} "
                       "-> {:g})",
                       before.diagonal, after.diagonal, before.area, after.area, before.volume, after.volume);
  return {};
}

/// Tries CGAL's exact autorefinement first (closed meshes), then its local repair; keeps a
/// result only when no self-intersection is left and the shape is kept, else leaves the mesh
/// as it was and says why.
void remove_self_intersections(CgalMesh& mesh, RepairResult& result) {
  if (!PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(mesh)) return;
  const Measures before = measure(mesh);
  const auto attempt = [&](const char* name, auto&& run) {
    CgalMesh candidate = mesh;
    bool fixed = false;
    try {
      fixed = run(candidate);
      candidate.collect_garbage();
    } catch (const std::exception& e) {
      result.failures.push_back(fmt::format("CGAL {} failed: {}", name, e.what()));
      return false;
    }
    if (!fixed || PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(candidate)) {
      result.failures.push_back(fmt::format("CGAL {} left self-intersections", name));
      return false;
    }
    const std::string changed = shape_change(before, measure(candidate));
    if (!changed.empty()) {
      result.failures.push_back(fmt::format("rejected the result of CGAL {}: {}", name, changed));
      return false;
    }
    mesh = std::move(candidate);
    result.actions.push_back(fmt::format("removed the self-intersections (CGAL {})", name));
    return true;
  };
  if (CGAL::is_closed(mesh) &&
      attempt("autorefine_and_remove_self_intersections", [](CgalMesh& m) {
        return PMP::experimental::autorefine_and_remove_self_intersections(m);
      }))
    return;
  if (attempt("remove_self_intersections", [](CgalMesh& m) {
        return PMP::experimental::remove_self_intersections(m, CGAL::parameters::preserve_genus(false));
      }))
    return;
  result.failures.push_back("could not remove the self-intersections");
}

/// 1. The soup: merge duplicate points, drop faces with repeated corners, duplicate faces and
///    unreferenced points. False when no face is left.
bool clean_soup(const SurfaceMesh& input, std::vector<Point>& points, std::vector<Polygon>& polygons,
                RepairResult& result) {
  points.reserve(input.vertices.size());
  for (const Vec3& v : input.vertices) points.push_back(detail::to_point(v));
  polygons.reserve(input.faces.size());
  for (const Tri& f : input.faces) polygons.push_back({f[0], f[1], f[2]});
  const std::size_t merged = PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  if (merged > 0) result.actions.push_back("merged " + plural(merged, "duplicate vertex", "duplicate vertices"));
  const std::size_t faces_before = polygons.size(), points_merged = points.size();
  PMP::repair_polygon_soup(points, polygons);
  if (polygons.size() < faces_before)
    result.actions.push_back("removed " + plural(faces_before - polygons.size(), "face", "faces") +
                             " with repeated corners or duplicating another face");
  if (points.size() < points_merged)
    result.actions.push_back("dropped " +
                             plural(points_merged - points.size(), "unreferenced vertex", "unreferenced vertices"));
  if (polygons.empty()) result.failures.push_back("no face is left after removing the degenerate ones");
  return !polygons.empty();
}

/// 2. Consistent orientation; points at non-manifold edges and vertices are duplicated.
void orient_soup(std::vector<Point>& points, std::vector<Polygon>& polygons, RepairResult& result) {
  const std::size_t points_before = points.size();
  PMP::orient_polygon_soup(points, polygons);
  if (points.size() > points_before)
    result.actions.push_back("split " + plural(points.size() - points_before, "vertex", "vertices") +
                             " at non-manifold edges or vertices (CGAL orient_polygon_soup)");
  if (result.before.inconsistent_edges > 0)
    result.actions.push_back("oriented the faces consistently (CGAL orient_polygon_soup)");
}

/// 3. Collinear (zero-area) faces: removed by edge collapses and flips, which keep the surface
///    closed where simply deleting them would open it.
void remove_collinear_faces(CgalMesh& mesh, RepairResult& result) {
  std::size_t collinear = 0;
  for (face_descriptor f : mesh.faces())
    if (PMP::is_degenerate_triangle_face(f, mesh)) ++collinear;
  if (collinear == 0) return;
  const bool all = PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  result.actions.push_back(fmt::format("removed {} by edge collapse{}",
                                       plural(collinear, "collinear (zero-area) face", "collinear (zero-area) faces"),
                                       all ? "" : " (some could not be removed)"));
  if (!all) result.failures.push_back("CGAL remove_degenerate_faces could not remove every zero-area face");
}

/// 4. Opt-in repairs, and the outward orientation.
void final_repairs(CgalMesh& mesh, const RepairOptions& options, RepairResult& result) {
  if (options.fill_holes && !CGAL::is_closed(mesh)) fill_holes(mesh, options, result);
  orient_outward(mesh, result);
  if (options.remove_self_intersections) {
    remove_self_intersections(mesh, result);
    orient_outward(mesh, result);
  }
}

}  // namespace

RepairResult repair_mesh(const SurfaceMesh& input, const RepairOptions& options) {
  RepairResult result;
  MeshCheckOptions check_options;
  check_options.self_intersections = options.check_self_intersections;
  result.before = check_mesh(input, check_options);
  if (result.before.ok()) {
    result.mesh = input;
    result.after = result.before;
    return result;
  }

  try {
    std::vector<Point> points;
    std::vector<Polygon> polygons;
    if (!clean_soup(input, points, polygons, result)) {
      result.mesh = {};
      result.after = check_mesh(result.mesh, check_options);
      result.changed = true;
      return result;
    }
    orient_soup(points, polygons, result);
    if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
      result.failures.push_back("the faces do not form a valid polygon mesh even after orient_polygon_soup");
      result.mesh = soup_to_surface(points, polygons);
    } else {
      CgalMesh mesh;
      PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
      remove_collinear_faces(mesh, result);
      final_repairs(mesh, options, result);
      result.mesh = to_surface(mesh);
    }
  } catch (const std::exception& e) {
    // CGAL signals broken preconditions with exceptions (when its checks are on): give back the
    // input unrepaired, with the reason.
    result.failures.push_back(std::string("CGAL failed during repair: ") + e.what());
    result.mesh = input;
  }

  result.changed = !same_mesh(result.mesh, input);
  result.after = check_mesh(result.mesh, check_options);
  return result;
}

}  // namespace medax::services
