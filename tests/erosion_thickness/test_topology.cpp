// Medial curves and skeletons keep the topology of the medial complex (Yan et al. 2016, §7;
// notes §9 "Topology"): chi, b0, b1 (b2 with closed surfaces); disk-like complexes give trees;
// theta1 = theta2 = inf gives a point for genus 0 and g cycles for genus g.
#include "erosion_thickness.hpp"
#include "fixtures.hpp"
#include "pure_complex.hpp"
#include "voronoi_fixture.hpp"

#include <medax/services/topology.hpp>
#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

using namespace medax;
using namespace medax::et;
namespace fx = medax::et::testing;
using services::ComplexTopology;
using services::complex_topology;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

MedialComplex curves_of(const MedialComplex& mc, double omega, Subdivision* sub_out = nullptr) {
  const auto run = run_erosion_thickness(mc, omega, 1);
  const Subdivision sub = build_subdivision(run->graph, run->burn);
  CHECK(sub.crossing_arcs == 0);
  CHECK(sub.unconnected_faces == 0);
  MedialComplex out = mc;
  store_medial_curves(extract_medial_curves(run->graph, sub), out);
  if (sub_out) *sub_out = sub;
  return out;
}

MedialComplex skeleton_of(const MedialComplex& mc, double omega, const SkeletonOptions& o, Skeleton* sk_out = nullptr) {
  const auto run = run_erosion_thickness(mc, omega, 1);
  const Subdivision sub = build_subdivision(run->graph, run->burn);
  CHECK(sub.crossing_arcs == 0);
  const Skeleton sk = compute_skeleton(run->graph, sub, run->loose_edges, o);
  MedialComplex out;
  store_skeleton(sk, out);
  if (sk_out) *sk_out = sk;
  return out;
}

SkeletonOptions minimal() {
  SkeletonOptions o;
  o.theta1 = o.theta2 = kInfinity;
  return o;
}

void require_same(const ComplexTopology& a, const ComplexTopology& b) {
  INFO("input chi " << a.euler << " b " << a.b0 << " " << a.b1 << " " << a.b2 << "; output chi " << b.euler << " b "
                    << b.b0 << " " << b.b1 << " " << b.b2);
  CHECK(a.euler == b.euler);
  CHECK(a.b0 == b.b0);
  CHECK(a.b1 == b.b1);
  CHECK(a.b2 == b.b2);
}

MedialComplex jittered_plate(unsigned seed) {
  MedialComplex mc = fx::make_plate(1.0, 0.7, 9, 7, fx::constant_radius(0.02));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> j(-0.03, 0.03);
  for (Vec3& p : mc.centres) {
    if (p.x() > 1e-9 && p.x() < 1 - 1e-9) p.x() += j(rng);
    if (p.y() > 1e-9 && p.y() < 0.7 - 1e-9) p.y() += j(rng);
  }
  return mc;
}

}  // namespace

TEST_CASE("Medial curves of disk-like complexes are trees") {
  for (const MedialComplex& mc : {fx::make_plate(1.0, 0.6, 10, 6, fx::constant_radius(0.05)),
                                  jittered_plate(1), jittered_plate(2),
                                  fx::make_book(1.0, 0.1, 0.3, 0.05, 20, 40)}) {
    for (double omega : {0.05, 0.02, 0.008}) {
      const MedialComplex c = curves_of(mc, omega);
      const ComplexTopology t = complex_topology(c);
      CHECK(c.faces.empty());
      CHECK(t.b0 == 1);
      CHECK(t.b1 == 0);
      CHECK(t.euler == 1);
    }
  }
}

TEST_CASE("Medial curves keep chi and Betti numbers: annulus and disjoint pieces") {
  MedialComplex annulus = fx::make_annulus(0.3, 0.6, 4, 24, 0.02);
  require_same(complex_topology(annulus), complex_topology(curves_of(annulus, 0.02)));
  // Two disjoint plates plus the annulus.
  MedialComplex many = annulus;
  const MedialComplex plate = fx::make_plate(0.5, 0.5, 4, 4, fx::constant_radius(0.01));
  for (int k = 0; k < 2; ++k) {
    const Index base = static_cast<Index>(many.num_vertices());
    for (std::size_t v = 0; v < plate.num_vertices(); ++v) many.add_vertex(plate.centres[v] + Vec3(2 + k, 0, 0), 0.01);
    for (const Tri& f : plate.faces) many.add_face(base + f[0], base + f[1], base + f[2]);
  }
  many.close_edges();
  const ComplexTopology t = complex_topology(many);
  CHECK(t.b0 == 3);
  require_same(t, complex_topology(curves_of(many, 0.02)));
}

TEST_CASE("Medial curves keep closed surfaces that never burn") {
  MedialComplex mc = fx::make_plate(1.0, 1.0, 4, 4, fx::constant_radius(0.1));
  fx::add_sphere(mc, Vec3(3, 0, 0), 0.5, 3, 0.1);
  // A sphere with a fin on one of its edges.
  const Index s0 = static_cast<Index>(mc.num_vertices());
  fx::add_sphere(mc, Vec3(6, 0, 0), 0.5, 2, 0.1);
  const Index ta = mc.add_vertex(mc.centres[s0] + Vec3(0, 0, 1), 0.1), tb = mc.add_vertex(mc.centres[s0 + 1] + Vec3(0, 0, 1), 0.1);
  mc.add_face(s0, s0 + 1, tb);
  mc.add_face(s0, tb, ta);
  mc.close_edges();
  const ComplexTopology t = complex_topology(mc);
  CHECK(t.b2 == 2);
  Subdivision sub;
  const MedialComplex c = curves_of(mc, 0.1, &sub);
  CHECK(sub.residue_triangles > 0);
  require_same(t, complex_topology(c));
  // ET_C is infinite on the closed surfaces' curve attachments, finite on the plate's tree.
  require_same(t, complex_topology(skeleton_of(mc, 0.1, minimal())));
}

TEST_CASE("ET_C is zero at the leaves of the medial curves and never negative") {
  const MedialComplex mc = jittered_plate(5);
  const MedialComplex c = curves_of(mc, 0.02);
  const auto& et_c = c.vertex_props.fields.get("et_c");
  std::vector<int> degree(c.num_vertices(), 0);
  for (const Segment& e : c.edges) ++degree[e[0]], ++degree[e[1]];
  std::size_t leaves = 0, zero = 0;
  double lowest = 0;
  for (std::size_t v = 0; v < c.num_vertices(); ++v) {
    lowest = std::min(lowest, et_c[v]);
    if (degree[v] != 1) continue;
    ++leaves;
    zero += std::abs(et_c[v]) < 1e-12;
  }
  INFO(leaves << " leaves, " << zero << " with ET_C = 0; lowest ET_C " << lowest);
  CHECK(leaves > 0);
  CHECK(lowest > -0.01);
  CHECK(zero >= 0.9 * leaves);
}

TEST_CASE("Skeleton with theta1 = theta2 = inf: a point for disks and a cycle for an annulus") {
  for (const MedialComplex& mc : {fx::make_plate(1.0, 0.6, 10, 6, fx::constant_radius(0.05)), jittered_plate(3),
                                  fx::make_book(1.0, 0.1, 0.3, 0.05, 20, 40)}) {
    const MedialComplex s = skeleton_of(mc, 0.02, minimal());
    CHECK(s.num_vertices() == 1);
    CHECK(s.edges.empty());
    CHECK(s.faces.empty());
  }
  const MedialComplex annulus = fx::make_annulus(0.3, 0.6, 4, 24, 0.02);
  const MedialComplex s = skeleton_of(annulus, 0.02, minimal());
  CHECK(s.faces.empty());
  CHECK(s.num_vertices() == s.edges.size());
  const ComplexTopology t = complex_topology(s);
  CHECK(t.b0 == 1);
  CHECK(t.b1 == 1);
  // The cycle follows the medial curves where it can: most of its edges are curve edges.
  const auto& curve = s.edge_props.labels.get("medial_curve");
  CHECK(std::count(curve.begin(), curve.end(), 1) >= 0.5 * curve.size());
}

TEST_CASE("Skeleton keeps every protected cell and the topology") {
  // The book scaled to unit max side: pages of height 0.1, 0.1 and 0.3, R = 0.005.
  const MedialComplex book = fx::make_book(1.0, 0.1, 0.3, 0.005, 30, 60);
  for (double theta2 : {0.02, 0.06, kInfinity})
    for (double theta1 : {0.01, 0.04, kInfinity}) {
      SkeletonOptions o;
      o.theta2 = theta2;
      o.theta1 = theta1;
      o.phi2 = 0;
      o.coarsen = false;  // the refined cells, to count the protected ones
      Skeleton sk;
      const MedialComplex s = skeleton_of(book, 0.01, o, &sk);
      require_same(complex_topology(book), complex_topology(s));
      o.coarsen = true;
      Skeleton coarse;
      const MedialComplex c = skeleton_of(book, 0.01, o, &coarse);
      require_same(complex_topology(book), complex_topology(c));
      CHECK(c.faces.size() <= s.faces.size());
      if (theta2 == 0.02) CHECK(coarse.coarse_triangles > 0);
      double kept = 0;  // area of the written triangles above theta2: the protected wedges
      for (std::size_t f = 0; f < sk.faces.size(); ++f)
        if (sk.face_priority[f] > theta2) {
          const Vec3 &a = sk.points[sk.faces[f][0]], &b = sk.points[sk.faces[f][1]], &c = sk.points[sk.faces[f][2]];
          kept += 0.5 * (b - a).cross(c - a).norm();
        }
      CHECK(kept == Approx(sk.protected_area).epsilon(1e-9));
      std::size_t curves = 0;
      for (std::size_t e = 0; e < sk.edges.size(); ++e) curves += sk.edge_curve[e] && sk.edge_priority[e] > theta1;
      CHECK(curves == sk.protected_curve_edges);
      if (theta2 == 0.02) CHECK(sk.protected_faces > 0);    // page 3 reaches ET 0.1
      if (theta2 == kInfinity) CHECK(s.faces.empty());    // all-curve skeleton
    }
}

TEST_CASE("Skeleton size filter phi2 drops small sheet components") {
  const MedialComplex book = fx::make_book(1.0, 0.1, 0.3, 0.005, 30, 60);
  SkeletonOptions o;
  o.theta2 = 0.02;
  o.theta1 = kInfinity;
  o.phi2 = 0;
  Skeleton a, b;
  skeleton_of(book, 0.01, o, &a);
  o.phi2 = 10.0;  // larger than the whole book: every sheet component goes
  skeleton_of(book, 0.01, o, &b);
  CHECK(a.protected_faces > 0);
  CHECK(b.protected_faces == 0);
  CHECK(b.dropped_sheet_components > 0);
  CHECK(b.faces.empty());
}

namespace {
/// Vertices jittered by 1e-4 so that the Voronoi diagram is generic (the fixtures' symmetric
/// meshes have many cospherical points, whose Voronoi vertices coincide).
MedialComplex voronoi_of(SurfaceMesh mesh) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1e-4, 1e-4);
  for (Vec3& p : mesh.vertices) p += Vec3(u(rng), u(rng), u(rng));
  MedialComplex mc = fx::interior_voronoi_complex(mesh);
  make_pure_complex(mc, 1e-9);
  return mc;
}
}  // namespace

TEST_CASE("Voronoi complexes of an ellipsoid a box and a flat torus: curves and skeletons keep the topology") {
  struct Case {
    const char* name;
    SurfaceMesh mesh;
    std::size_t genus;
  };
  std::vector<Case> cases;
  cases.push_back({"ellipsoid", medax::testing::make_ellipsoid(0.5, 0.35, 0.2, 3), 0});
  cases.push_back({"box", medax::testing::make_box(0.5, 0.35, 0.2, 8), 0});
  SurfaceMesh torus = medax::testing::make_torus(0.35, 0.12, 48, 16);
  for (Vec3& p : torus.vertices) p.z() *= 0.5;  // elliptic tube: the medial axis is an annulus
  cases.push_back({"flat torus", torus, 1});
  for (Case& c : cases) {
    const MedialComplex mc = voronoi_of(c.mesh);
    const ComplexTopology t = complex_topology(mc);
    INFO(c.name << ": " << mc.num_vertices() << " vertices, " << mc.faces.size() << " faces; chi " << t.euler << " b "
                << t.b0 << " " << t.b1 << " " << t.b2);
    CHECK(t.b0 == 1);
    CHECK(t.b1 == c.genus);
    CHECK(t.b2 == 0);
    require_same(t, complex_topology(curves_of(mc, 0.004)));
    const MedialComplex minimal_skeleton = skeleton_of(mc, 0.004, minimal());
    require_same(t, complex_topology(minimal_skeleton));
    // A point for genus 0, one cycle for genus 1.
    CHECK(minimal_skeleton.faces.empty());
    if (c.genus == 0) CHECK(minimal_skeleton.num_vertices() == 1);
    else CHECK(minimal_skeleton.num_vertices() == minimal_skeleton.edges.size());
    SkeletonOptions defaults;
    Skeleton sk;
    require_same(t, complex_topology(skeleton_of(mc, 0.004, defaults, &sk)));
    CHECK(sk.protected_faces > 0);
  }
}
