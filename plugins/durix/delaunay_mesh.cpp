// Dyer–Zhang–Möller 2007 Delaunay mesh construction (notes §1.2): flip or split every mesh edge
// that is not an edge of the 3D Delaunay tetrahedralization (DT) of the vertices, then split every
// remaining non-Delaunay face at its centroid, and sweep again until a sweep changes nothing.
// New points go into the DT incrementally (never rebuilt). Edge splits sit on "concentric shells"
// (powers of two around an original endpoint), which is what makes the splitting terminate.
#include "delaunay_mesh.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace medax::durix {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
using Mesh = CGAL::Surface_mesh<Point>;
using VD = Mesh::Vertex_index;
using HD = Mesh::Halfedge_index;
using ED = Mesh::Edge_index;
using FD = Mesh::Face_index;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point to_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The mesh with its DT, kept in sync: every mesh vertex has its DT vertex.
class Converter {
 public:
  Converter(const SurfaceMesh& input, const DelaunayMeshOptions& options, DelaunayMeshReport& report,
            const std::function<void()>& check_cancelled)
      : options_(options), report_(report), check_cancelled_(check_cancelled) {
    original_count_ = input.vertices.size();
    std::vector<std::pair<Point, std::uint32_t>> points;
    points.reserve(input.vertices.size());
    for (std::size_t i = 0; i < input.vertices.size(); ++i) {
      mesh_.add_vertex(to_point(input.vertices[i]));
      points.emplace_back(to_point(input.vertices[i]), static_cast<std::uint32_t>(i));
    }
    for (std::size_t f = 0; f < input.faces.size(); ++f) {
      const Tri& t = input.faces[f];
      const FD fd = mesh_.add_face(VD(t[0]), VD(t[1]), VD(t[2]));
      if (fd == Mesh::null_face())
        throw std::runtime_error("face " + std::to_string(f) +
                                 " cannot be added to a manifold halfedge mesh (non-manifold edge or vertex, or "
                                 "inconsistent orientation); run `repair` first");
    }
    for (auto h : mesh_.halfedges())
      if (mesh_.is_border(h))
        throw std::runtime_error("the mesh has boundary edges (holes); close them first (`repair` with fill_holes)");
    dt_.insert(points.begin(), points.end());
    if (dt_.number_of_vertices() != input.vertices.size())
      throw std::runtime_error(std::to_string(input.vertices.size() - dt_.number_of_vertices()) +
                               " vertices share the position of another vertex; merge them first (`repair`)");
    if (dt_.dimension() < 3) throw std::runtime_error("the vertices are coplanar: there is no solid");
    handle_.assign(input.vertices.size(), Dt::Vertex_handle());
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v) handle_[v->info()] = v;
    max_insertions_ = static_cast<std::size_t>(options.max_insertions_factor * double(input.vertices.size())) + 1000;
    max_lawson_flips_ = 100 * input.faces.size() + 10000;
  }

  bool is_dt_edge(VD a, VD b) const {
    Dt::Cell_handle c;
    int i, j;
    return dt_.is_edge(handle_[a], handle_[b], c, i, j);
  }
  bool is_dt_facet(FD f) const {
    const HD h = mesh_.halfedge(f);
    const VD a = mesh_.source(h), b = mesh_.target(h), c = mesh_.target(mesh_.next(h));
    Dt::Cell_handle cell;
    int i, j, k;
    return dt_.is_facet(handle_[a], handle_[b], handle_[c], cell, i, j, k);
  }

  void count_before() {
    for (auto e : mesh_.edges())
      if (!is_dt_edge(mesh_.vertex(e, 0), mesh_.vertex(e, 1))) ++report_.non_delaunay_edges_before;
    for (auto f : mesh_.faces())
      if (!is_dt_facet(f)) ++report_.non_delaunay_faces_before;
  }

  void run() {
    count_before();
    for (int sweep = 0;; ++sweep) {
      if (sweep >= options_.max_sweeps)
        throw std::runtime_error("no Delaunay mesh after " + std::to_string(options_.max_sweeps) +
                                 " sweeps of flips and splits");
      ++report_.sweeps;
      std::size_t changes = sweep_edges();
      // Faces whose three edges are Delaunay but which are not facets: split at the centroid.
      const std::size_t nf = mesh_.number_of_faces();
      for (std::size_t i = 0; i < nf; ++i) {
        const FD f(static_cast<Mesh::size_type>(i));
        if (is_dt_facet(f)) continue;
        split_face(f);
        ++changes;
      }
      if (changes == 0) break;
    }
  }

  SurfaceMesh result() const {
    SurfaceMesh out;
    out.vertices.reserve(mesh_.number_of_vertices());
    for (auto v : mesh_.vertices()) out.vertices.push_back(to_vec(mesh_.point(v)));
    out.faces.reserve(mesh_.number_of_faces());
    for (auto f : mesh_.faces()) {
      const HD h = mesh_.halfedge(f);
      out.faces.push_back({static_cast<Index>(mesh_.source(h)), static_cast<Index>(mesh_.target(h)),
                           static_cast<Index>(mesh_.target(mesh_.next(h)))});
    }
    return out;
  }

 private:
  /// Processes every edge once, plus the edges that flips and splits create or disturb.
  std::size_t sweep_edges() {
    std::deque<ED> queue;
    std::vector<char> queued(mesh_.number_of_edges(), 1);
    for (auto e : mesh_.edges()) queue.push_back(e);
    const auto push = [&](HD h) {
      const ED e = mesh_.edge(h);
      if (e.idx() >= queued.size()) queued.resize(e.idx() + 1, 0);
      if (!queued[e.idx()]) {
        queued[e.idx()] = 1;
        queue.push_back(e);
      }
    };
    std::size_t changes = 0, steps = 0;
    while (!queue.empty()) {
      const ED e = queue.front();
      queue.pop_front();
      queued[e.idx()] = 0;
      if ((++steps & 1023) == 0 && check_cancelled_) check_cancelled_();
      const HD h = mesh_.halfedge(e);
      if (is_dt_edge(mesh_.source(h), mesh_.target(h))) continue;
      ++changes;
      if (options_.flips && try_flip(h)) {
        ++report_.flips;
        // The DT did not change, but the four edges of the quad have new opposite vertices (they
        // may have become flippable), and a Lawson flip's new edge may itself not be Delaunay.
        push(h);
        push(mesh_.next(h));
        push(mesh_.prev(h));
        push(mesh_.next(mesh_.opposite(h)));
        push(mesh_.prev(mesh_.opposite(h)));
        continue;
      }
      const VD v = split_edge(h);
      for (HD g : CGAL::halfedges_around_target(v, mesh_)) {
        push(g);
        push(mesh_.next(g));
      }
      // A new point may remove DT edges anywhere near it: the next sweep re-checks everything.
    }
    return changes;
  }

  static Vec3 normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

  static double angle(const Vec3& apex, const Vec3& p, const Vec3& q) {
    const Vec3 u = p - apex, v = q - apex;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  }

  /// Flips the non-Delaunay edge of h when the flip keeps the surface (small dihedral angle, no
  /// fold, no existing edge, no vertex left with two edges) and either the new edge is a DT edge
  /// or the edge is not locally Delaunay on the surface (opposite angles summing to more than the
  /// new edge's: Lawson's flip, which is how a flat region reaches its Delaunay triangulation).
  bool try_flip(HD h) {
    const HD o = mesh_.opposite(h);
    const VD a = mesh_.source(h), b = mesh_.target(h);
    const VD c = mesh_.target(mesh_.next(h)), d = mesh_.target(mesh_.next(o));
    if (c == d) return false;
    if (CGAL::degree(a, mesh_) <= 3 || CGAL::degree(b, mesh_) <= 3) return false;
    if (CGAL::halfedge(c, d, mesh_).second) return false;
    const Vec3 pa = to_vec(mesh_.point(a)), pb = to_vec(mesh_.point(b)), pc = to_vec(mesh_.point(c)),
               pd = to_vec(mesh_.point(d));
    const Vec3 n1 = normal(pa, pb, pc), n2 = normal(pb, pa, pd);
    const double l1 = n1.norm(), l2 = n2.norm();
    if (l1 == 0 || l2 == 0) return false;
    const double cos_feature = std::cos(options_.feature_angle_deg * M_PI / 180.0);
    if (n1.dot(n2) < cos_feature * l1 * l2) return false;
    const Vec3 avg = n1 / l1 + n2 / l2;
    // After the flip the faces are (c, a, d) and (d, b, c).
    const Vec3 m1 = normal(pc, pa, pd), m2 = normal(pd, pb, pc);
    if (m1.dot(avg) <= 0 || m2.dot(avg) <= 0) return false;
    if (m1.norm() <= 1e-12 * (l1 + l2) || m2.norm() <= 1e-12 * (l1 + l2)) return false;
    const bool delaunay_target = is_dt_edge(c, d);
    if (!delaunay_target) {
      const double before = angle(pc, pa, pb) + angle(pd, pa, pb);  // opposite angles of ab
      const double after = angle(pa, pc, pd) + angle(pb, pc, pd);   // opposite angles of cd
      if (before <= after + 1e-12 || ++lawson_flips_ > max_lawson_flips_) return false;
    }
    CGAL::Euler::flip_edge(h, mesh_);
    return true;
  }

  /// Inserts p into the DT and returns its handle; throws when the budget is exhausted or p
  /// falls on an existing vertex.
  Dt::Vertex_handle insert(const Point& p, std::uint32_t id, Dt::Cell_handle hint) {
    if (++insertions_ > max_insertions_)
      throw std::runtime_error("gave up after inserting " + std::to_string(max_insertions_) +
                               " points: the flips and splits do not converge on this mesh (splits cascade near sliver "
                               "triangles, thin parts or nearly flat creases); remesh it first, or raise max_insertions");
    const std::size_t before = dt_.number_of_vertices();
    Dt::Vertex_handle vh = dt_.insert(p, hint);
    if (dt_.number_of_vertices() != before + 1)
      throw std::runtime_error("a split point coincides with an existing vertex (the mesh is too thin or degenerate "
                               "here to be made Delaunay in double precision)");
    vh->info() = id;
    if (handle_.size() <= id) handle_.resize(id + 1);
    handle_[id] = vh;
    return vh;
  }

  /// Splits the edge of h at a concentric-shell point, and both its faces.
  VD split_edge(HD h) {
    const VD a = mesh_.source(h), b = mesh_.target(h);
    const Vec3 pa = to_vec(mesh_.point(a)), pb = to_vec(mesh_.point(b));
    const double length = (pb - pa).norm();
    const bool a_orig = a.idx() < original_count_, b_orig = b.idx() < original_count_;
    Vec3 p;
    if (a_orig || b_orig) {
      // Shell around the original endpoint (the lower index when both are original).
      const bool around_a = a_orig && (!b_orig || a.idx() < b.idx());
      const Vec3 centre = around_a ? pa : pb, other = around_a ? pb : pa;
      const double k = std::floor(std::log2(length / 2));
      const double s1 = std::exp2(k), s2 = std::exp2(k + 1);
      const double s = (length / 2 - s1 <= s2 - length / 2) ? s1 : s2;
      p = centre + (other - centre) * (s / length);
    } else {
      p = 0.5 * (pa + pb);
    }
    Dt::Vertex_handle existing;
    if (dt_.is_vertex(to_point(p), existing)) p = 0.5 * (pa + pb);  // rounding hit a vertex: midpoint
    const std::uint32_t id = static_cast<std::uint32_t>(mesh_.number_of_vertices());
    insert(to_point(p), id, handle_[a]->cell());
    const HD hnew = CGAL::Euler::split_edge(h, mesh_);  // target(hnew) is the new vertex
    const VD v = mesh_.target(hnew);
    mesh_.point(v) = to_point(p);
    if (v.idx() != id) throw std::logic_error("unexpected vertex numbering after a split");
    CGAL::Euler::split_face(hnew, mesh_.next(h), mesh_);
    const HD oh = mesh_.opposite(h);
    CGAL::Euler::split_face(oh, mesh_.next(mesh_.opposite(hnew)), mesh_);
    ++report_.edge_splits;
    return v;
  }

  void split_face(FD f) {
    const HD h = mesh_.halfedge(f);
    const Vec3 pa = to_vec(mesh_.point(mesh_.source(h))), pb = to_vec(mesh_.point(mesh_.target(h))),
               pc = to_vec(mesh_.point(mesh_.target(mesh_.next(h))));
    const Vec3 p = (pa + pb + pc) / 3.0;
    const std::uint32_t id = static_cast<std::uint32_t>(mesh_.number_of_vertices());
    insert(to_point(p), id, handle_[mesh_.source(h)]->cell());
    const HD hc = CGAL::Euler::add_center_vertex(h, mesh_);
    const VD v = mesh_.target(hc);
    mesh_.point(v) = to_point(p);
    if (v.idx() != id) throw std::logic_error("unexpected vertex numbering after a split");
    ++report_.face_splits;
  }

  const DelaunayMeshOptions& options_;
  DelaunayMeshReport& report_;
  const std::function<void()>& check_cancelled_;
  Mesh mesh_;
  Dt dt_;
  std::vector<Dt::Vertex_handle> handle_;
  std::size_t original_count_ = 0;
  std::size_t insertions_ = 0, max_insertions_ = 0;
  std::size_t lawson_flips_ = 0, max_lawson_flips_ = 0;
};

}  // namespace

std::string DelaunayCheck::describe() const {
  std::ostringstream s;
  if (duplicate_points) s << duplicate_points << " vertices repeat the position of another vertex; ";
  s << non_delaunay_faces << " of " << faces << " faces are not facets of the Delaunay tetrahedralization of the "
    << "vertices";
  if (first_bad_face >= 0) s << " (first: face " << first_bad_face << ")";
  return s.str();
}

DelaunayCheck check_delaunay_mesh(const SurfaceMesh& mesh) {
  DelaunayCheck check;
  check.faces = mesh.faces.size();
  std::vector<std::pair<Point, std::uint32_t>> points;
  points.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    points.emplace_back(to_point(mesh.vertices[i]), static_cast<std::uint32_t>(i));
  Dt dt(points.begin(), points.end());
  std::vector<Dt::Vertex_handle> handle(mesh.vertices.size());
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) handle[v->info()] = v;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (handle[i] == Dt::Vertex_handle() || handle[i]->info() != i) ++check.duplicate_points;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Tri& t = mesh.faces[f];
    bool ok = false;
    if (t[0] < handle.size() && t[1] < handle.size() && t[2] < handle.size() && handle[t[0]] != Dt::Vertex_handle() &&
        handle[t[1]] != Dt::Vertex_handle() && handle[t[2]] != Dt::Vertex_handle() && handle[t[0]]->info() == t[0] &&
        handle[t[1]]->info() == t[1] && handle[t[2]]->info() == t[2] && dt.dimension() == 3) {
      Dt::Cell_handle c;
      int i, j, k;
      ok = dt.is_facet(handle[t[0]], handle[t[1]], handle[t[2]], c, i, j, k);
    }
    if (!ok) {
      if (check.first_bad_face < 0) check.first_bad_face = static_cast<long long>(f);
      ++check.non_delaunay_faces;
    }
  }
  return check;
}

SurfaceMesh make_delaunay_mesh(const SurfaceMesh& mesh, const DelaunayMeshOptions& options, DelaunayMeshReport* report,
                               const std::function<void()>& check_cancelled) {
  const auto t0 = std::chrono::steady_clock::now();
  DelaunayMeshReport local;
  DelaunayMeshReport& r = report ? *report : local;
  r = {};
  r.input_vertices = mesh.vertices.size();
  r.input_faces = mesh.faces.size();
  if (mesh.faces.empty()) throw std::runtime_error("the mesh has no faces");
  Converter converter(mesh, options, r, check_cancelled);
  converter.run();
  SurfaceMesh out = converter.result();
  const auto t1 = std::chrono::steady_clock::now();
  const DelaunayCheck check = check_delaunay_mesh(out);
  r.seconds_verify = seconds_since(t1);
  if (!check.ok())
    throw std::runtime_error("the converted mesh does not verify on a fresh tetrahedralization: " + check.describe());
  r.output_vertices = out.vertices.size();
  r.output_faces = out.faces.size();
  r.seconds = seconds_since(t0);
  return out;
}

}  // namespace medax::durix
