// Restricted-Delaunay remeshing with CGAL Mesh_3 (notes §1.2 option 2). Mesh_3 rather than the
// older make_surface_mesh: it is the maintained mesher (Surface_mesher is deprecated), takes a
// triangle mesh as its domain directly, and has a `manifold()` topology option. Its
// triangulation is a regular triangulation; without feature protection, perturbation and
// exudation every weight stays zero, so it is the Delaunay tetrahedralization of its vertices.
// Kept in its own file: Mesh_3 is the slowest CGAL code of the package to compile.
#include "remesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_3/Dump_c3t3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/refine_mesh_3.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <unordered_map>

namespace medax::durix {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Polyhedron = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_3<Polyhedron, K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

}  // namespace
}  // namespace medax::durix

// Before reporting some errors Mesh_3 writes its whole complex to dump-bug.* in the working
// directory; a library must not write there (the error itself still reaches the caller).
template <bool streamable>
struct CGAL::Dump_c3t3<medax::durix::C3t3, streamable> {
  void dump_c3t3(const medax::durix::C3t3&, const std::string&) const {}
};

namespace medax::durix {
namespace {

Polyhedron to_cgal(const SurfaceMesh& mesh) {
  Polyhedron out;
  for (const Vec3& v : mesh.vertices) out.add_vertex(Point(v.x(), v.y(), v.z()));
  for (const Tri& t : mesh.faces) {
    using VI = Polyhedron::Vertex_index;
    if (out.add_face(VI(t[0]), VI(t[1]), VI(t[2])) == Polyhedron::null_face())
      throw std::invalid_argument("remesh: the input is not a manifold, consistently oriented triangle mesh; run "
                                  "`repair` first");
  }
  return out;
}

double mean_edge_length(const SurfaceMesh& mesh) {
  double sum = 0;
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k) sum += (mesh.vertices[t[(k + 1) % 3]] - mesh.vertices[t[k]]).norm();
  return sum / (3.0 * double(mesh.faces.size()));
}

/// Every k-th input vertex, as initial surface points of the mesher. Mesh_3's own initial points
/// (rays shot from the box centre) can miss whole parts: on lamp (a thin shell) they gave no
/// surface facet at all, and a component no ray hits is never meshed. Input vertices lie on the
/// surface, reach every part the stride reaches, and need no random draw.
void insert_initial_points(const SurfaceMesh& mesh, std::size_t count, const Domain& domain, C3t3& c3t3) {
  const auto weighted = c3t3.triangulation().geom_traits().construct_weighted_point_3_object();
  const Domain::Index index = domain.index_from_surface_patch_index(domain.make_surface_index());
  const std::size_t stride = std::max<std::size_t>(1, mesh.vertices.size() / std::max<std::size_t>(1, count));
  for (std::size_t i = 0; i < mesh.vertices.size(); i += stride) {
    const Vec3& v = mesh.vertices[i];
    const Tr::Vertex_handle vh = c3t3.triangulation().insert(weighted(Point(v.x(), v.y(), v.z())));
    if (vh == Tr::Vertex_handle()) continue;
    c3t3.set_dimension(vh, 2);
    c3t3.set_index(vh, index);
  }
}

/// The facets between a cell of the complex and one outside it, each oriented so that the inner
/// cell's fourth vertex lies below it (outward normal); vertices numbered in order of first use.
SurfaceMesh boundary_of_cells(const C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  SurfaceMesh out;
  std::unordered_map<Tr::Vertex_handle, Index> index;
  const auto id = [&](Tr::Vertex_handle v) {
    const auto [it, inserted] = index.emplace(v, static_cast<Index>(out.vertices.size()));
    if (inserted) {
      const Point& p = tr.point(v).point();
      out.vertices.emplace_back(p.x(), p.y(), p.z());
    }
    return it->second;
  };
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    for (int i = 0; i < 4; ++i) {
      if (c3t3.is_in_complex(c->neighbor(i))) continue;
      Tr::Vertex_handle a = c->vertex(Tr::vertex_triple_index(i, 0)), b = c->vertex(Tr::vertex_triple_index(i, 1)),
                        d = c->vertex(Tr::vertex_triple_index(i, 2));
      if (CGAL::orientation(tr.point(a).point(), tr.point(b).point(), tr.point(d).point(),
                            tr.point(c->vertex(i)).point()) == CGAL::POSITIVE)
        std::swap(b, d);
      out.faces.push_back({id(a), id(b), id(d)});
    }
  }
  return out;
}

}  // namespace

SurfaceMesh remesh_restricted_delaunay(const SurfaceMesh& mesh, const RemeshOptions& options, RemeshReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  if (mesh.faces.empty()) throw std::invalid_argument("remesh: the mesh has no faces");
  RemeshReport local;
  RemeshReport& r = report ? *report : local;
  r = {};
  r.facet_size = options.facet_size * mean_edge_length(mesh);
  r.facet_distance = options.facet_distance * bbox_diagonal(mesh.vertices);
  if (!(r.facet_size > 0) || !(r.facet_distance > 0))
    throw std::invalid_argument("remesh: facet_size and facet_distance must be positive");

  const Polyhedron polyhedron = to_cgal(mesh);
  const Domain domain(polyhedron);
  namespace p = CGAL::parameters;
  const Criteria criteria(p::facet_angle = options.facet_angle_deg, p::facet_size = r.facet_size,
                          p::facet_distance = r.facet_distance,
                          p::cell_radius_edge_ratio = options.cell_radius_edge_ratio);
  C3t3 c3t3;
  insert_initial_points(mesh, options.initial_points, domain, c3t3);
  // A vertex cap: on some inputs (lamp, a thin shell) the manifold refinement does not stop
  // before the memory is gone.
  const std::size_t max_vertices = options.max_vertices_factor * mesh.vertices.size() + options.max_vertices_base;
  CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
  try {
    CGAL::refine_mesh_3(c3t3, domain, criteria, p::no_perturb(), p::no_exude(), p::no_lloyd(), p::no_odt(),
                        p::manifold(),
                        p::mesh_3_options(p::maximal_number_of_vertices = max_vertices,
                                          p::pointer_to_error_code = &error));
  } catch (const CGAL::Failure_exception& e) {
    throw RemeshRefinementError("Mesh_3 stopped on an internal error (" + e.message() + ")");
  }
  if (error != CGAL::CGAL_MESH_3_NO_ERROR)
    throw RemeshRefinementError("the remesh reached its cap of " + std::to_string(max_vertices) +
                                " vertices before meeting the facet criteria (thin parts or near-touching surfaces)");
  SurfaceMesh out = boundary_of_cells(c3t3);
  r.mesh3_vertices = c3t3.triangulation().number_of_vertices();
  r.restricted_facets = c3t3.number_of_facets_in_complex();
  r.inside_cells = c3t3.number_of_cells_in_complex();
  r.output_vertices = out.vertices.size();
  r.output_faces = out.faces.size();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace medax::durix
