#include "reconstruction.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace medax::msd {
namespace {

/// Narrow band half width in voxels: enough for the union's minimum to be exact near the surface.
constexpr float kHalfWidth = 3.0f;

struct Box {
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 high = Vec3::Constant(std::numeric_limits<double>::lowest());
};

Box bounds(const std::vector<SurfaceMesh>& solids) {
  Box box;
  for (const SurfaceMesh& s : solids)
    for (const Vec3& x : s.vertices) {
      box.low = box.low.cwiseMin(x);
      box.high = box.high.cwiseMax(x);
    }
  return box;
}

/// A solid's level set; coordinates relative to `origin` so that floats keep their precision.
openvdb::FloatGrid::Ptr level_set(const SurfaceMesh& solid, const Vec3& origin,
                                  const openvdb::math::Transform& transform) {
  std::vector<openvdb::Vec3s> points;
  for (const Vec3& x : solid.vertices) {
    const Vec3 local = x - origin;
    points.emplace_back(static_cast<float>(local.x()), static_cast<float>(local.y()), static_cast<float>(local.z()));
  }
  std::vector<openvdb::Vec3I> triangles;
  for (const Tri& f : solid.faces)
    triangles.emplace_back(static_cast<unsigned>(f[0]), static_cast<unsigned>(f[1]), static_cast<unsigned>(f[2]));
  return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(transform, points, triangles, kHalfWidth);
}

/// The zero level set as triangles (OpenVDB's quads split along one diagonal), back at `origin`.
SurfaceMesh mesh_zero_level(const openvdb::FloatGrid& grid, const Vec3& origin) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0.0, 0.0);
  SurfaceMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const openvdb::Vec3s& x : points) mesh.vertices.push_back(origin + Vec3(x.x(), x.y(), x.z()));
  const auto index = [](unsigned i) { return static_cast<Index>(i); };
  for (const openvdb::Vec3I& t : triangles) mesh.faces.push_back({index(t[0]), index(t[1]), index(t[2])});
  for (const openvdb::Vec4I& q : quads) {
    mesh.faces.push_back({index(q[0]), index(q[1]), index(q[2])});
    mesh.faces.push_back({index(q[0]), index(q[2]), index(q[3])});
  }
  return mesh;
}

/// Six times the enclosed volume (positive for outward faces).
double signed_volume6(const SurfaceMesh& mesh) {
  double total = 0;
  for (const Tri& f : mesh.faces)
    total += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  return total;
}

/// Outward faces whatever OpenVDB's winding convention.
void orient_outward(SurfaceMesh& mesh) {
  if (signed_volume6(mesh) >= 0) return;
  for (Tri& f : mesh.faces) std::swap(f[1], f[2]);
}

double voxel_size(const Box& box, const SdfOptions& options) {
  if (!(box.low.x() <= box.high.x())) return 0;  // no vertex
  return (box.high - box.low).maxCoeff() / std::max(1, options.resolution);
}

}  // namespace

std::vector<SurfaceMesh> fitted_surfaces(const std::vector<Primitive>& primitives) {
  std::vector<SurfaceMesh> solids;
  for (const Primitive& p : primitives)
    if (p.fitted) solids.push_back(primitive_mesh(p));
  return solids;
}

std::vector<SurfaceMesh> refined_surfaces(const std::vector<RefinedPrimitive>& refined) {
  std::vector<SurfaceMesh> solids;
  for (const RefinedPrimitive& r : refined)
    if (!r.mesh.faces.empty()) solids.push_back(r.mesh);
  return solids;
}

double sdf_voxel_size(const std::vector<SurfaceMesh>& solids, const SdfOptions& options) {
  return voxel_size(bounds(solids), options);
}

ReconstructedSurface reconstruct_sdf(const std::vector<SurfaceMesh>& input, const Similarity& to_input,
                                     const SdfOptions& options) {
  std::vector<const SurfaceMesh*> solids;
  for (const SurfaceMesh& s : input)
    if (!s.faces.empty()) solids.push_back(&s);
  const Box box = bounds(input);
  const double voxel = voxel_size(box, options);
  if (solids.empty() || !(voxel > 0))
    throw std::invalid_argument("no primitive surface to build Ŝ from (every primitive failed or was left out)");
  openvdb::initialize();
  const Vec3 origin = box.low;
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel);
  // One level set per solid in parallel (a solid alone keeps OpenVDB's own threads idle), then the
  // union in the solids' order.
  std::vector<openvdb::FloatGrid::Ptr> grids(solids.size());
  tbb::parallel_for(std::size_t{0}, solids.size(),
                    [&](std::size_t k) { grids[k] = level_set(*solids[k], origin, *transform); });
  openvdb::FloatGrid::Ptr united = grids.front();
  for (std::size_t k = 1; k < grids.size(); ++k) {
    openvdb::tools::csgUnion(*united, *grids[k]);  // the minimum of the two distances
    grids[k].reset();
  }
  ReconstructedSurface result;
  result.surface = mesh_zero_level(*united, origin);
  orient_outward(result.surface);
  result.to_input = to_input;
  result.method = fmt::format("signed distance, {} voxels across (voxel {:.3g}), union of {} primitives (OpenVDB)",
                              options.resolution, voxel, solids.size());
  return result;
}

}  // namespace medax::msd
