#pragma once
// The local significance measures that Yan et al. 2016 compare ET with (§2, §8; notes §7), on
// the generators of each medial vertex (its nearest boundary points):
//   - object angle: the largest angle at the centre between two generators (radians);
//   - circumradius (the lambda of the lambda-medial axis, Chazal & Lieutier 2004): the radius
//     of the smallest ball enclosing the generators.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <string>
#include <vector>

namespace medax::et {

struct Ball {
  Vec3 centre = Vec3::Zero();
  double radius = -1;  ///< -1 for the empty ball
};

/// Smallest enclosing ball (Welzl's algorithm; degenerate supports handled by trying their
/// subsets).
Ball min_enclosing_ball(std::vector<Vec3> points);

/// Largest pairwise angle (radians) at `centre` between the directions to `points`; 0 with
/// fewer than two points.
double max_pairwise_angle(const Vec3& centre, const std::vector<Vec3>& points);

/// Generator positions of every medial vertex: from `medial.generators` (kind "mesh_vertex"
/// indexes shape.mesh.vertices, "sample" indexes shape.samples.points) when present; otherwise
/// the surface points (mesh vertices, or samples without a mesh) whose distance to the centre is
/// at most (1 + tolerance) times the nearest one's. Throws std::invalid_argument when neither
/// is available. `source` says which was used.
std::vector<std::vector<Vec3>> medial_generators(const Shape& shape, const MedialComplex& medial,
                                                 double tolerance, std::string* source = nullptr);

}  // namespace medax::et
