#pragma once
// The input side of the data model: a triangle mesh and/or oriented surface samples.
#include <medax/geometry.hpp>

#include <string>
#include <vector>

namespace medax {

/// An indexed triangle mesh. Plain arrays keep the public SDK free of heavy headers; kernel
/// services convert to CGAL/OpenMesh structures inside their .cpp files.
struct SurfaceMesh {
  std::vector<Vec3> vertices;
  std::vector<Tri> faces;

  bool empty() const { return faces.empty(); }
};

/// Oriented point samples of a surface: position, outward unit normal, and the surface area
/// each sample stands for (areas sum to the surface area).
struct OrientedSamples {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  std::vector<double> areas;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

/// The shape every stage sees: the mesh as conditioned so far, optional samples, and the map
/// from the current frame back to the input file's frame.
struct Shape {
  SurfaceMesh mesh;
  OrientedSamples samples;
  Similarity to_input;  ///< current frame -> input frame
  std::string source;   ///< path of the file it was read from
};

/// Axis-aligned bounding box diagonal length of a point set (0 when empty).
double bbox_diagonal(const std::vector<Vec3>& points);

}  // namespace medax
