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

namespace {

/// The face a draw lands in: the first whose cumulative area exceeds the target, as
/// std::upper_bound finds it, through a guide table. Bucket b of the table covers the targets in
/// [bound[b], bound[b + 1]) and starts at first[b] = upper_bound(bound[b]): a search reads a
/// bucket's few faces instead of 17 levels of a binary search over a large mesh's faces. A
/// target the rounding of the bucket bounds puts outside its bucket is searched in full.
class FacePicker {
 public:
  explicit FacePicker(const std::vector<double>& cumulative)
      : cumulative_(cumulative), buckets_(cumulative.size()), bound_(buckets_ + 1), first_(buckets_ + 1) {
    const double total = cumulative.back();
    for (std::size_t b = 0; b <= buckets_; ++b) {
      bound_[b] = total * static_cast<double>(b) / static_cast<double>(buckets_);
      first_[b] = search(0, cumulative.size(), bound_[b]);
    }
  }
  std::size_t operator()(double target) const {
    const auto b = std::min(buckets_ - 1, static_cast<std::size_t>(target / cumulative_.back() * buckets_));
    if (!(bound_[b] <= target && target < bound_[b + 1])) return search(0, cumulative_.size(), target);
    return search(first_[b], std::min(cumulative_.size(), first_[b + 1] + 1), target);
  }

 private:
  std::size_t search(std::size_t from, std::size_t to, double target) const {
    return static_cast<std::size_t>(
        std::upper_bound(cumulative_.begin() + from, cumulative_.begin() + to, target) - cumulative_.begin());
  }
  const std::vector<double>& cumulative_;
  std::size_t buckets_;
  std::vector<double> bound_;
  std::vector<std::size_t> first_;
};

}  // namespace

OrientedSamples sample_uniform(const SurfaceMesh& mesh, std::size_t count, std::mt19937_64& rng) {
  const std::vector<double> areas = face_areas(mesh);
  const std::vector<Vec3> normals = face_normals(mesh);
  std::vector<double> cumulative(areas.size());
  std::partial_sum(areas.begin(), areas.end(), cumulative.begin());
  const double total = cumulative.empty() ? 0.0 : cumulative.back();
  if (!(total > 0)) throw std::invalid_argument("cannot sample a mesh with zero area");
  const FacePicker pick(cumulative);
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
        const std::size_t f = std::min<std::size_t>(pick(target), areas.size() - 1);
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
