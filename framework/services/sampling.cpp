#include <medax/services/sampling.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace medax::services {

std::vector<Vec3> face_normals(const SurfaceMesh& mesh) {
  std::vector<Vec3> normals(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& [a, b, c] = mesh.faces[f];
    const Vec3 n = (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]);
    const double len = n.norm();
    normals[f] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  return normals;
}

std::vector<double> face_areas(const SurfaceMesh& mesh) {
  std::vector<double> areas(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& [a, b, c] = mesh.faces[f];
    areas[f] = 0.5 * (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]).norm();
  }
  return areas;
}

double surface_area(const SurfaceMesh& mesh) {
  const auto areas = face_areas(mesh);
  double total = 0;
  for (double a : areas) total += a;
  return total;
}

OrientedSamples vertex_samples(const SurfaceMesh& mesh) {
  OrientedSamples s;
  s.points = mesh.vertices;
  s.normals.assign(mesh.vertices.size(), Vec3::Zero());
  s.areas.assign(mesh.vertices.size(), 0.0);
  for (const Tri& f : mesh.faces) {
    // The un-normalised cross product is the area-weighted normal (twice the area).
    const Vec3 n = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    for (Index v : f) {
      s.normals[v] += n;
      s.areas[v] += n.norm() / 6.0;
    }
  }
  for (Vec3& n : s.normals) {
    const double len = n.norm();
    if (len > 0) n /= len;
  }
  return s;
}

OrientedSamples sample_uniform(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng) {
  const std::vector<double> areas = face_areas(mesh);
  const std::vector<Vec3> normals = face_normals(mesh);
  std::vector<double> cumulative(areas.size());
  std::partial_sum(areas.begin(), areas.end(), cumulative.begin());
  const double total = cumulative.empty() ? 0.0 : cumulative.back();
  if (!(total > 0)) throw std::invalid_argument("cannot sample a mesh with zero area");
  OrientedSamples s;
  s.points.resize(count);
  s.normals.resize(count);
  s.areas.assign(count, total / static_cast<double>(count));
  // Explicit arithmetic instead of std distributions, whose output differs between library
  // implementations: the same seed gives the same samples everywhere.
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  // Three draws per sample, in sample order (face, then u and v), drawn a block at a time; the
  // samples of a block are then placed in parallel, so the result does not depend on threads.
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  std::vector<double> draws;
  for (std::size_t first = 0; first < count; first += kBlock) {
    const std::size_t n = std::min(kBlock, count - first);
    draws.resize(3 * n);
    for (double& x : draws) x = uniform();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const double target = draws[3 * k] * total;
        const std::size_t f = std::min<std::size_t>(
            static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), target) -
                                     cumulative.begin()),
            areas.size() - 1);
        double u = draws[3 * k + 1], v = draws[3 * k + 2];
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const auto& [a, b, c] = mesh.faces[f];
        s.points[first + k] =
            mesh.vertices[a] + u * (mesh.vertices[b] - mesh.vertices[a]) + v * (mesh.vertices[c] - mesh.vertices[a]);
        s.normals[first + k] = normals[f];
      }
    });
  }
  return s;
}

}  // namespace medax::services
