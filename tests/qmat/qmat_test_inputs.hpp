#pragma once
// Inputs shared by the qmat tests: the interior Voronoi axis of a mesh.
#include "interior_voronoi.hpp"

#include <medax/io.hpp>

#include <test_paths.hpp>

namespace medax::test {

/// The interior Voronoi axis (vertices, edges, faces) of the mesh's vertices.
inline MedialComplex voronoi_axis(const SurfaceMesh& mesh) {
  return voronoi::interior_voronoi(mesh.vertices, mesh);
}
inline MedialComplex voronoi_axis(const std::string& data_file) {
  return voronoi_axis(read_mesh(data_dir() / data_file));
}

}  // namespace medax::test
