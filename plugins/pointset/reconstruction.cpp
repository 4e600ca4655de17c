// Poisson (CGAL::poisson_surface_reconstruction_delaunay) and advancing-front
// (CGAL::advancing_front_surface_reconstruction) reconstruction into a SurfaceMesh.
#include "reconstruction.hpp"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/property_map.h>

#include <array>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace medax::pointset {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointNormal = std::pair<Point, Vector>;

std::vector<Point> cgal_points(const OrientedSamples& cloud) {
  std::vector<Point> points;
  points.reserve(cloud.size());
  for (const Vec3& p : cloud.points) points.emplace_back(p.x(), p.y(), p.z());
  return points;
}

SurfaceMesh poisson(const OrientedSamples& cloud, const ReconstructionOptions& options) {
  if (cloud.normals.size() != cloud.size())
    throw std::invalid_argument("Poisson reconstruction needs oriented normals: put a `normals` stage before it, or "
                                "use `method: advancing_front`");
  std::vector<PointNormal> points;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    points.emplace_back(Point(cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z()),
                        Vector(cloud.normals[i].x(), cloud.normals[i].y(), cloud.normals[i].z()));
  const CGAL::First_of_pair_property_map<PointNormal> point_map;
  const CGAL::Second_of_pair_property_map<PointNormal> normal_map;
  const double spacing =
      CGAL::compute_average_spacing<CGAL::Sequential_tag>(points, 6, CGAL::parameters::point_map(point_map));
  CGAL::Surface_mesh<Point> mesh;
  const bool ok = CGAL::poisson_surface_reconstruction_delaunay(points.begin(), points.end(), point_map, normal_map,
                                                                mesh, spacing, options.angle, 30.0, options.distance);
  if (!ok || mesh.number_of_faces() == 0)
    throw std::runtime_error("Poisson reconstruction gave no surface: check that the normals point outward "
                             "consistently (`normals` stage with `orient: true`), or use `method: advancing_front`");
  SurfaceMesh out;
  std::map<CGAL::Surface_mesh<Point>::Vertex_index, Index> index;
  for (const auto v : mesh.vertices()) {
    index[v] = static_cast<Index>(out.vertices.size());
    const Point& p = mesh.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : mesh.faces()) {
    Tri tri{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) tri[k++ % 3] = index[v];
    if (k == 3) out.faces.push_back(tri);
  }
  return out;
}

SurfaceMesh advancing_front(const OrientedSamples& cloud, const ReconstructionOptions& options) {
  const std::vector<Point> points = cgal_points(cloud);
  std::vector<std::array<std::size_t, 3>> triangles;
  CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(triangles),
                                               options.radius_ratio_bound);
  if (triangles.empty())
    throw std::runtime_error("advancing-front reconstruction gave no triangle: the cloud is too sparse or too "
                             "noisy; smooth it (`smooth_points`) or raise `radius_ratio_bound`");
  SurfaceMesh out;
  out.vertices = cloud.points;
  for (const auto& t : triangles)
    out.faces.push_back({static_cast<Index>(t[0]), static_cast<Index>(t[1]), static_cast<Index>(t[2])});
  return out;
}

std::size_t count_border_edges(const SurfaceMesh& mesh) {
  std::map<std::pair<Index, Index>, int> uses;
  for (const Tri& f : mesh.faces)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(f[k], f[(k + 1) % 3])];
  std::size_t border = 0;
  for (const auto& [edge, count] : uses) border += count == 1;
  return border;
}

}  // namespace

SurfaceMesh reconstruct_surface(const OrientedSamples& cloud, const ReconstructionOptions& options,
                                ReconstructionReport* report) {
  SurfaceMesh mesh =
      options.method == ReconstructionMethod::Poisson ? poisson(cloud, options) : advancing_front(cloud, options);
  if (report) report->border_edges = count_border_edges(mesh);
  return mesh;
}

}  // namespace medax::pointset
