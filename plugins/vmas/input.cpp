#include "input.hpp"

#include <medax/services/closest_point.hpp>
#include <medax/services/kdtree.hpp>
#include <medax/services/sampling.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace medax::vmas {

namespace {

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

/// The frame of the input: origin at the box centre, scale its largest side.
void set_frame(VmasInput& in, const Box& box, const char* degenerate) {
  in.origin = 0.5 * (box.lo + box.hi);
  in.scale = (box.hi - box.lo).maxCoeff();
  in.diagonal = (box.hi - box.lo).norm();
  if (!(in.scale > 0)) throw std::invalid_argument(degenerate);
}

/// A vertex's sums of weighted tangent planes: the plane quadric of eq. 5/7, and the authors'
/// rows Σ √w (n·(v − q) − r) as (a, β).
struct PlaneSums {
  Quadric q;
  Vec4 a = Vec4::Zero();
  double beta = 0;
  void add(const Vec3& p, const Vec3& n, double w) {
    q += Quadric::plane(p, n, w);
    a += std::sqrt(w) * Vec4(n.x(), n.y(), n.z(), 1.0);
    beta += std::sqrt(w) * n.dot(p);
  }
  PackedQuadric quadric() const { return PackedQuadric::from(q); }
  PackedQuadric author_quadric() const { return PackedQuadric::from(Quadric::row(a, beta)); }
};

/// The k nearest other points of every point (closest first), in parallel.
std::vector<std::vector<Index>> knn_lists(const services::PointIndex& kd, const std::vector<Vec3>& points,
                                          std::size_t k) {
  std::vector<std::vector<Index>> lists(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t v) {
    const auto found = kd.k_nearest(points[v], k + 1);
    auto& list = lists[v];
    list.reserve(k);
    for (const auto& [u, d] : found)
      if (u != v && list.size() < k) list.push_back(u);
  });
  return lists;
}

std::vector<Segment> edges_of_lists(const std::vector<std::vector<Index>>& lists) {
  std::vector<Segment> edges;
  for (Index v = 0; v < lists.size(); ++v)
    for (Index u : lists[v]) edges.push_back({std::min(u, v), std::max(u, v)});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace

VmasInput::VmasInput() = default;
VmasInput::~VmasInput() = default;

std::vector<Segment> mesh_edges(const std::vector<Tri>& faces) {
  std::vector<Segment> edges;
  edges.reserve(faces.size() * 3);
  for (const Tri& f : faces)
    for (int i = 0; i < 3; ++i) {
      const Index a = f[i], b = f[(i + 1) % 3];
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<Segment> knn_edges(const std::vector<Vec3>& points, std::size_t k) {
  services::PointIndex kd(points);
  return edges_of_lists(knn_lists(kd, points, k));
}

std::shared_ptr<const VmasInput> VmasInput::from_mesh(const SurfaceMesh& mesh, const InputOptions& options) {
  if (mesh.faces.empty()) throw std::invalid_argument("the mesh has no faces");
  std::shared_ptr<VmasInput> in(new VmasInput());
  in->kind = InputKind::Mesh;
  in->options = options;
  Box box;
  for (const Tri& f : mesh.faces)
    for (Index v : f) {
      if (v >= mesh.vertices.size()) throw std::invalid_argument("a face refers to a missing vertex");
      box.add(mesh.vertices[v]);
    }
  set_frame(*in, box, "the mesh is degenerate (zero extent)");

  const std::size_t n = mesh.vertices.size();
  SurfaceMesh local;
  local.faces = mesh.faces;
  local.vertices.resize(n);
  for (std::size_t v = 0; v < n; ++v) local.vertices[v] = mesh.vertices[v] - in->origin;
  in->points = local.vertices;
  in->triangles = mesh.faces;
  in->face_normals_ = services::face_normals(local);
  const std::vector<double> face_area = services::face_areas(local);

  std::vector<PlaneSums> planes(n);
  std::vector<Vec3> normal_sum(n, Vec3::Zero());
  in->areas.assign(n, 0.0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Vec3& nf = in->face_normals_[f];
    const double w = face_area[f] / 3.0;
    if (!(w > 0)) continue;
    for (Index v : mesh.faces[f]) {
      planes[v].add(in->points[v], nf, w);  // eq. 7: the plane through v with the face normal
      in->areas[v] += w;                    // eq. 6: A(v) = Σ A(t)/3
      normal_sum[v] += face_area[f] * nf;   // area-weighted vertex normal
    }
  }
  in->normals.resize(n);
  in->quadrics.resize(n);
  in->author_quadrics.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const double len = normal_sum[v].norm();
    in->normals[v] = len > 0 ? Vec3(normal_sum[v] / len) : Vec3::Zero();
    in->quadrics[v] = planes[v].quadric();
    in->author_quadrics[v] = planes[v].author_quadric();
  }
  in->graph_edges = mesh_edges(mesh.faces);
  in->aabb_ = std::make_unique<services::SurfaceDistance>(local);
  in->finish_setup();
  return in;
}

std::shared_ptr<const VmasInput> VmasInput::from_samples(const OrientedSamples& samples, const InputOptions& options) {
  const std::size_t n = samples.points.size();
  if (n < options.knn + 1) throw std::invalid_argument("too few samples for the kNN graph");
  if (samples.normals.size() != n)
    throw std::invalid_argument("point-cloud input needs one normal per sample (shape.samples.normals)");
  if (options.knn < 1) throw std::invalid_argument("knn_k must be at least 1");
  std::shared_ptr<VmasInput> in(new VmasInput());
  in->kind = InputKind::Cloud;
  in->options = options;
  Box box;
  for (const Vec3& p : samples.points) box.add(p);
  set_frame(*in, box, "the samples are degenerate (zero extent)");
  in->points.resize(n);
  in->normals.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    in->points[v] = samples.points[v] - in->origin;
    const double len = samples.normals[v].norm();
    in->normals[v] = len > 0 ? Vec3(samples.normals[v] / len) : Vec3::Zero();
  }
  in->kd_ = std::make_unique<services::PointIndex>(in->points);
  const std::size_t k = options.knn;
  const auto knn = knn_lists(*in->kd_, in->points, k);
  // Support area as in the authors' code (after Zhao et al. 2023): (Σ_u |u − v|)² / (2k).
  in->areas.assign(n, 0.0);
  for (std::size_t v = 0; v < n; ++v) {
    double sum = 0;
    for (Index u : knn[v]) sum += (in->points[u] - in->points[v]).norm();
    in->areas[v] = sum * sum / (2.0 * static_cast<double>(k));
  }
  // Eq. 5 with v itself among its neighbours: Σ_{u ∈ {v} ∪ kNN(v)} A(u)/(k+1) · Q_{u, n_u}.
  in->quadrics.resize(n);
  in->author_quadrics.resize(n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t v) {
    PlaneSums planes;
    const auto add = [&](Index u) { planes.add(in->points[u], in->normals[u], in->areas[u] / static_cast<double>(k + 1)); };
    add(static_cast<Index>(v));
    for (Index u : knn[v]) add(u);
    in->quadrics[v] = planes.quadric();
    in->author_quadrics[v] = planes.author_quadric();
  });
  in->graph_edges = edges_of_lists(knn);
  in->finish_setup();
  return in;
}

void VmasInput::finish_setup() {
  if (!kd_) kd_ = std::make_unique<services::PointIndex>(points);
  if (!options.shrinking_balls) return;
  vertex_balls.resize(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t v) {
    if (normals[v].squaredNorm() == 0 || !(areas[v] > 0)) {
      vertex_balls[v] = {points[v], 0.0};
      return;
    }
    vertex_balls[v] = shrinking_ball(points[v], normals[v]);
    // A ball that never shrank found no second contact: not a medial ball (never a seed).
    if (!(vertex_balls[v].radius < 0.999 * options.sb_initial_radius * diagonal) || !vertex_balls[v].centre.allFinite())
      vertex_balls[v] = {points[v], 0.0};
  });
}

// The shrinking ball (Ma et al. 2012): the ball tangent at p (inward along −n) shrinks to the
// ball through p and the contact q closest to its centre, r = |p − q|² / 2n·(p − q), until no
// contact is closer than r. Contacts are the input's points (k-d tree) or the closest points on
// the faces (AABB tree: the CGAL port, with its stops: q within 1e-3·scale of p, the same face
// twice, a ball that would shrink below sb_min_radius). Both stop when p and q are seen from the
// centre within sb_angle_deg (denoising; masbcpp and the CGoGN code also ask |q − p| < r, which
// any angle below 60° implies: |q − p| = 2r·sin(θ/2)).
Sphere VmasInput::shrinking_ball(const Vec3& p, const Vec3& n) const {
  const bool on_faces = options.sb_contacts == BallContacts::Faces && aabb_;
  const double tolerance = options.sb_tolerance * scale;
  const double min_cos = std::cos(options.sb_angle_deg * M_PI / 180.0);
  double r = options.sb_initial_radius * diagonal;
  Vec3 c = p - r * n;
  Vec3 q_prev = p - 2 * r * n;
  Index last_face = 0;
  for (int j = 0; j <= options.sb_max_iterations; ++j) {
    Vec3 q;
    if (on_faces) {
      const services::ClosestPoint cp = aabb_->closest(c);
      q = cp.point;
      if (cp.distance >= r - tolerance || (q - p).norm() <= 1e-3 * scale || (j > 0 && cp.face == last_face)) break;
      last_face = cp.face;
    } else {
      const auto [qi, d] = kd_->nearest(c);
      q = points[qi];
      if (std::abs(d - r) <= tolerance || (q - q_prev).norm() < tolerance) break;
    }
    const double den = n.dot(p - q);
    if (den <= 0) break;
    const double r_new = (p - q).squaredNorm() / (2 * den);
    if (on_faces && r_new < options.sb_min_radius * scale) break;
    const Vec3 c_new = p - r_new * n;
    if (j > 0) {
      const Vec3 a = (p - c_new).normalized(), b = (q - c_new).normalized();
      if (a.dot(b) > min_cos) break;  // p and q at too small an angle: a noise bump
    }
    c = c_new;
    r = r_new;
    q_prev = q;
  }
  return {c, r};
}

Index VmasInput::nearest_vertex(const Vec3& p) const { return kd_->nearest(p).first; }

Sphere VmasInput::correct(const Sphere& s) const {
  Vec3 p, np;
  if (aabb_) {
    const services::ClosestPoint cp = aabb_->closest(s.centre);
    p = cp.point;
    np = face_normals_[cp.face];
  } else {
    const Index i = kd_->nearest(s.centre).first;
    p = points[i];
    np = normals[i];
  }
  Vec3 dir = p - s.centre;
  const double len = dir.norm();
  dir = len > 1e-12 * scale ? Vec3(dir / len) : np;
  if (dir.dot(np) <= 0) dir = -dir;  // the ball always grows inward, even from an outside centre
  const Sphere b = shrinking_ball(p, dir);
  const double r0 = options.sb_initial_radius * diagonal;
  if (std::isfinite(b.radius) && b.radius > 0 && b.radius < 0.999 * r0 && b.centre.allFinite()) return b;
  // The ball did not shrink (no second contact was found): fall back on the nearest vertex's ball.
  const Index v = nearest_vertex(p);
  if (!vertex_balls.empty() && vertex_balls[v].radius > 0) return vertex_balls[v];
  return normals[v].squaredNorm() > 0 ? shrinking_ball(points[v], normals[v]) : s;
}

}  // namespace medax::vmas
