// MSD skeleton construction, step c: the restricted Delaunay triangulation and its thinning.
#include "construction_rdt.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <map>

namespace medax::msd {
namespace {

/// The cells of a polygon in angular order around their centroid, in their best-fit plane.
std::vector<Index> angular_order(std::vector<Index> cells, const std::vector<Vec3>& sites) {
  Vec3 centre = Vec3::Zero();
  for (Index c : cells) centre += sites[c];
  centre /= static_cast<double>(cells.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (Index c : cells) cov += (sites[c] - centre) * (sites[c] - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 u = eig.eigenvectors().col(2), v = eig.eigenvectors().col(1);
  std::vector<std::pair<double, Index>> by_angle;
  for (Index c : cells) by_angle.push_back({std::atan2((sites[c] - centre).dot(v), (sites[c] - centre).dot(u)), c});
  std::sort(by_angle.begin(), by_angle.end());
  std::vector<Index> out;
  for (const auto& a : by_angle) out.push_back(a.second);
  return out;
}

void add_triangle(Rdt& rdt, Index a, Index b, Index c) {
  rdt.triangles.insert(sorted_tri(a, b, c));
  rdt.edges.insert(sorted_pair(a, b));
  rdt.edges.insert(sorted_pair(b, c));
  rdt.edges.insert(sorted_pair(c, a));
}

double triangle_area(const std::vector<Vec3>& p, const Tri& t) {
  return 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
}

}  // namespace

Rdt dual_complex(const SplitMesh& split, const std::vector<Vec3>& sites, ConstructionStats& stats) {
  Rdt rdt;
  std::set<std::vector<Index>> polygons;
  for (const auto& [key, list] : split.key_pieces) {
    const auto cells = cells_at(split, list);
    if (cells.size() == 2) rdt.edges.insert(sorted_pair(cells[0], cells[1]));
    if (cells.size() == 3) add_triangle(rdt, cells[0], cells[1], cells[2]);
    if (cells.size() >= 4) polygons.insert(cells);
  }
  for (const auto& cells : polygons) {
    const auto ring = angular_order(cells, sites);
    for (std::size_t k = 1; k + 1 < ring.size(); ++k) add_triangle(rdt, ring[0], ring[k], ring[k + 1]);
  }
  stats.polygons = polygons.size();
  return rdt;
}

std::size_t thin_tetrahedra(Rdt& rdt, const std::vector<Vec3>& points) {
  std::size_t thinned = 0;
  for (;;) {
    std::map<Tri, int> tets_of_face;
    for (const auto& t : rdt.triangles)
      for (Index d = 0; d < points.size(); ++d) {
        if (d <= t[2]) continue;  // each tetrahedron once, from its three lowest vertices
        const Tri f1 = sorted_tri(t[0], t[1], d), f2 = sorted_tri(t[0], t[2], d), f3 = sorted_tri(t[1], t[2], d);
        if (rdt.triangles.count(f1) && rdt.triangles.count(f2) && rdt.triangles.count(f3))
          for (const auto& f : {t, f1, f2, f3}) ++tets_of_face[f];
      }
    if (tets_of_face.empty()) return thinned;
    const Tri* best = nullptr;
    for (const auto& [face, count] : tets_of_face)
      if (count == 1 && (!best || triangle_area(points, face) < triangle_area(points, *best))) best = &face;
    if (!best) best = &tets_of_face.begin()->first;  // every face shared: open the first
    rdt.triangles.erase(*best);
    ++thinned;
  }
}

}  // namespace medax::msd
