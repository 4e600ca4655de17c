#pragma once
// The VMAS input, precomputed once (notes §2.2, §3): per surface vertex its position, normal,
// area, diffused SQEM quadric and shrinking ball; the neighbour graph (mesh edges, or the
// symmetrised kNN graph of a point cloud); and the closest-point queries of the correction step.
//
// Positions are stored relative to the bounding-box centre (`origin`): the quadrics then stay
// well conditioned wherever the shape sits, and a translated input gives the same numbers.
#include "quadric.hpp"

#include <medax/surface.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace medax::services {
class PointIndex;
class SurfaceDistance;
}  // namespace medax::services

namespace medax::vmas {

enum class InputKind { Mesh, Cloud };

/// Where a shrinking ball finds its second contact: the nearest input vertex (k-d tree, Ma et al.
/// 2012 and the CGoGN code) or the nearest point on the mesh's faces (AABB tree, the CGAL port).
enum class BallContacts { Vertices, Faces };

inline const std::vector<std::pair<std::string, BallContacts>> kBallContacts{{"vertices", BallContacts::Vertices},
                                                                             {"faces", BallContacts::Faces}};

struct InputOptions {
  std::size_t knn = 6;              ///< k of the kNN graph and diffused quadrics (clouds)
  bool shrinking_balls = true;      ///< precompute SB[v] for every vertex (splits, first sphere)
  double sb_initial_radius = 1.0;   ///< r0 of the shrinking ball, × bbox diagonal
  int sb_max_iterations = 30;
  double sb_tolerance = 1e-5;       ///< × scale (max bbox side)
  double sb_angle_deg = 20.0;       ///< denoising angle
  BallContacts sb_contacts = BallContacts::Vertices;  ///< faces: meshes only (clouds use their points)
  double sb_min_radius = 0.01;      ///< faces: a ball stops before shrinking below this, × scale
};

class VmasInput {
 public:
  /// A closed triangle mesh: eqs. 6–7 (planes through the vertex with its faces' normals).
  static std::shared_ptr<const VmasInput> from_mesh(const SurfaceMesh& mesh, const InputOptions& options = {});
  /// An oriented point cloud: eqs. 4–5 with the authors' kNN support areas (notes §2.2).
  static std::shared_ptr<const VmasInput> from_samples(const OrientedSamples& samples,
                                                       const InputOptions& options = {});
  ~VmasInput();
  VmasInput(const VmasInput&) = delete;
  VmasInput& operator=(const VmasInput&) = delete;

  InputKind kind = InputKind::Mesh;
  Vec3 origin = Vec3::Zero();  ///< bbox centre; positions below are relative to it
  double scale = 1;            ///< largest bbox side (the "unit box" of the paper's thresholds)
  double diagonal = 1;         ///< bbox diagonal
  InputOptions options;

  std::vector<Vec3> points;    ///< local frame
  std::vector<Vec3> normals;   ///< outward unit (area-weighted vertex normals for meshes)
  std::vector<double> areas;   ///< A(v)
  std::vector<PackedQuadric> quadrics;         ///< Q_v, the paper's sum of plane quadrics
  std::vector<PackedQuadric> author_quadrics;  ///< the authors' code: one summed row per vertex
  std::vector<Segment> graph_edges;            ///< u < w, sorted, unique
  std::vector<Tri> triangles;                  ///< mesh faces (empty for clouds)
  std::vector<Sphere> vertex_balls;            ///< SB[v], local frame (empty if not asked)

  std::size_t size() const { return points.size(); }
  /// Vertices with zero area (unused by any face) take part in nothing.
  bool active(Index v) const { return areas[v] > 0; }

  /// Shrinking ball at surface point p with outward unit normal n (local frame).
  Sphere shrinking_ball(const Vec3& p, const Vec3& n) const;
  /// The correction step (notes §2.6): closest surface point p of the centre, direction from the
  /// centre to p oriented outward by p's normal, shrinking ball from p. Local frame.
  Sphere correct(const Sphere& s) const;
  /// The closest input vertex to a point (local frame).
  Index nearest_vertex(const Vec3& p) const;

 private:
  VmasInput();
  void finish_setup();
  std::unique_ptr<services::PointIndex> kd_;
  std::unique_ptr<services::SurfaceDistance> aabb_;
  std::vector<Vec3> face_normals_;
};

/// The unique undirected edges of a triangle mesh, u < w, sorted.
std::vector<Segment> mesh_edges(const std::vector<Tri>& faces);
/// The symmetrised kNN graph of a point set (self excluded), u < w, sorted.
std::vector<Segment> knn_edges(const std::vector<Vec3>& points, std::size_t k);

}  // namespace medax::vmas
