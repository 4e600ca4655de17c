#pragma once
// Oriented samples of a triangle mesh.
#include <medax/surface.hpp>

#include <random>

namespace medax::services {

/// Unit outward normal of every face (zero for a degenerate face) and face areas.
std::vector<Vec3> face_normals(const SurfaceMesh& mesh);
std::vector<double> face_areas(const SurfaceMesh& mesh);
double surface_area(const SurfaceMesh& mesh);

/// The mesh vertices as samples: area-weighted vertex normals, a third of each incident
/// face's area per vertex.
OrientedSamples vertex_samples(const SurfaceMesh& mesh);

/// `count` points uniformly distributed by area, with face normals; areas = total / count.
OrientedSamples sample_uniform(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng);

}  // namespace medax::services
