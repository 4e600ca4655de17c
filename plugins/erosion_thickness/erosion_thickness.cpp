#include "erosion_thickness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace medax::et {

namespace {

double max_side(const std::vector<Vec3>& pts) {
  if (pts.empty()) return 0.0;
  Vec3 lo = pts[0], hi = pts[0];
  for (const Vec3& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return (hi - lo).maxCoeff();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// FNV-1a over 64-bit words: enough to tell two complexes apart, not a cryptographic hash.
class WordHash {
 public:
  void add(std::uint64_t w) {
    h_ ^= w;
    h_ *= 0x100000001b3ull;
  }
  void add(double d) {
    std::uint64_t w;
    std::memcpy(&w, &d, sizeof w);
    add(w);
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace

double reference_length(const Shape& shape, const MedialComplex& medial, RelativeTo relative_to) {
  if (relative_to == RelativeTo::Absolute) return 1.0;
  double l = 0;
  if (relative_to == RelativeTo::ShapeMaxSide)
    l = !shape.mesh.vertices.empty() ? max_side(shape.mesh.vertices) : max_side(shape.samples.points);
  if (!(l > 0)) l = max_side(medial.centres);
  if (!(l > 0)) l = 1.0;
  return l;
}

std::unique_ptr<EtRun> run_erosion_thickness(const MedialComplex& medial, double omega, int min_samples,
                                             const std::function<void()>& cancel) {
  auto run = std::make_unique<EtRun>();
  const auto t0 = std::chrono::steady_clock::now();
  run->complex = build_triangle_complex(medial.centres, medial.radii, medial.faces);
  // Listed edges that are no side of a triangle.
  std::vector<std::uint64_t> sides;
  sides.reserve(run->complex.edges.size());
  for (const Segment& e : run->complex.edges) sides.push_back((std::uint64_t(e[0]) << 32) | e[1]);
  for (const Segment& e : medial.edges) {
    if (e[0] == e[1]) continue;
    const Index a = std::min(e[0], e[1]), b = std::max(e[0], e[1]);
    if (!std::binary_search(sides.begin(), sides.end(), (std::uint64_t(a) << 32) | b))
      run->loose_edges.push_back({a, b});
  }
  std::sort(run->loose_edges.begin(), run->loose_edges.end());
  run->loose_edges.erase(std::unique(run->loose_edges.begin(), run->loose_edges.end()), run->loose_edges.end());
  run->graph = build_burn_graph(run->complex, omega, min_samples);
  run->seconds_graph = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  run->burn = burn(run->graph, cancel);
  run->seconds_burn = seconds_since(t1);
  return run;
}

ComplexFingerprint fingerprint(const MedialComplex& medial) {
  ComplexFingerprint f;
  f.vertices = medial.num_vertices();
  f.edges = medial.edges.size();
  f.faces = medial.faces.size();
  WordHash h;
  for (const Vec3& c : medial.centres) h.add(c.x()), h.add(c.y()), h.add(c.z());
  for (double r : medial.radii) h.add(r);
  for (const Segment& e : medial.edges) h.add((std::uint64_t(e[0]) << 32) | e[1]);
  for (const Tri& t : medial.faces) h.add((std::uint64_t(t[0]) << 32) | t[1]), h.add(std::uint64_t(t[2]));
  f.hash = h.value();
  return f;
}

std::string to_string(const ComplexFingerprint& f) {
  return fmt::format("V {} E {} F {}", f.vertices, f.edges, f.faces);
}

void store_erosion_thickness(const EtRun& run, MedialComplex& medial) {
  const std::size_t nv = medial.num_vertices();
  auto& bt = medial.add(kBt);
  auto& et = medial.add(kEt);
  for (std::size_t v = 0; v < nv; ++v) {
    bt[v] = run.burn.bt[v];
    et[v] = std::isinf(bt[v]) ? kInf : bt[v] - medial.radii[v];
  }
  auto& fet = medial.add(kFaceEt);
  for (std::size_t f = 0; f < medial.faces.size(); ++f) {
    double s = 0;
    for (Index v : medial.faces[f]) s += et[v];
    fet[f] = std::isinf(s) ? kInf : s / 3;
  }
}

void store_medial_curves(const MedialCurves& c, MedialComplex& medial) {
  MedialComplex out;
  out.centres = c.points;
  out.radii = c.radius;
  out.edges = c.edges;
  out.faces = c.faces;
  out.close_edges();
  out.add(kBtM) = c.bt_m;
  out.add(kBtC) = c.bt_c;
  out.add(kEtC) = c.et_c;
  auto& kind = out.add(kCurveKind);
  std::copy(c.kind.begin(), c.kind.end(), kind.begin());
  auto& eet = out.add(kEdgeEtC);
  for (std::size_t e = 0; e < out.edges.size(); ++e) {
    const double a = c.et_c[out.edges[e][0]], b = c.et_c[out.edges[e][1]];
    eet[e] = std::isinf(a) || std::isinf(b) ? kInf : 0.5 * (a + b);
  }
  medial = std::move(out);
}

void store_skeleton(const Skeleton& s, MedialComplex& medial) {
  MedialComplex out;
  out.centres = s.points;
  out.radii = s.radius;
  out.faces = s.faces;
  // Edges sorted (i < j), with their per-edge values.
  std::vector<std::size_t> order(s.edges.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto sorted = [&](std::size_t i) {
    return std::make_pair(std::min(s.edges[i][0], s.edges[i][1]), std::max(s.edges[i][0], s.edges[i][1]));
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sorted(a) < sorted(b); });
  for (std::size_t k : order) {
    const auto [a, b] = sorted(k);
    out.edges.push_back({a, b});
  }
  auto& curve = out.add(kMedialCurve);
  auto& eet = out.add(kEdgeEtC);
  for (std::size_t k = 0; k < order.size(); ++k) {
    curve[k] = s.edge_curve[order[k]];
    eet[k] = s.edge_curve[order[k]] ? s.edge_priority[order[k]] : std::numeric_limits<double>::quiet_NaN();
  }
  out.add(kBt) = s.bt;
  out.add(kEt) = s.et;
  out.add(kEtC) = s.et_c;
  auto& kind = out.add(kEtPoint);
  std::copy(s.kind.begin(), s.kind.end(), kind.begin());
  out.add(kFaceEt) = s.face_priority;
  medial = std::move(out);
}

}  // namespace medax::et
