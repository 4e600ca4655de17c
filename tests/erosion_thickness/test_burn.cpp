// Burn on the sampled graph (Yan et al. 2016 §6): the exact solutions of the implementation notes
// §9 (rounded plate, three-page book), 1D trees against brute force, and the invariants.
#include "burn.hpp"
#include "burn_1d.hpp"
#include "erosion_thickness.hpp"
#include "fixtures.hpp"
#include "medial_curves.hpp"
#include "pure_complex.hpp"
#include "voronoi_fixture.hpp"

#include <medax/testing/shapes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>

using namespace medax;
using namespace medax::et;
namespace fx = medax::et::testing;
using medax::et::testing::make_book;
using medax::et::testing::make_plate;

namespace {

struct Burned {
  std::unique_ptr<EtRun> run;
  const BurnGraph& g() const { return run->graph; }
  const BurnResult& r() const { return run->burn; }
};

Burned burn_complex(const MedialComplex& mc, double omega, int min_samples = 1) {
  return {run_erosion_thickness(mc, omega, min_samples)};
}

double plate_exact_distance(const Vec3& p, double w, double h) {
  return std::min({p.x(), w - p.x(), p.y(), h - p.y()});
}

/// Largest error BT_G - BT_exact over all nodes; also checks BT_G >= exact (graph paths are
/// never shorter than the geodesics they approximate).
template <typename Exact>
double max_error(const Burned& b, Exact exact) {
  double worst = 0;
  for (Index n = 0; n < b.g().num_nodes(); ++n) {
    const double e = exact(b.g().pos[n]);
    const double got = b.r().bt[n];
    REQUIRE(got >= e - 1e-9);
    worst = std::max(worst, got - e);
  }
  return worst;
}

/// Invariants of notes §9 for a burned complex whose R is Lipschitz on every arc.
void check_invariants(const Burned& b) {
  const BurnGraph& g = b.g();
  const BurnResult& r = b.r();
  for (Index n = 0; n < g.num_nodes(); ++n) {
    const double bt = r.bt[n];
    if (std::isinf(bt)) continue;
    // ET >= 0 under the Lipschitz condition; BT = R on ∂G.
    CHECK(bt - g.radius[n] >= -1e-9);
    if (g.boundary[n]) {
      CHECK(bt == Approx(g.radius[n]).margin(1e-12));
      continue;
    }
    // BT = max over sectors with a primary arc of BT(u) + |uv|, and some neighbour is lower.
    double best = -1;
    int primes = 0;
    for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
      if (r.prime_node[s] != kNone) {
        ++primes;
        const Index u = r.prime_node[s];
        best = std::max(best, r.bt[u] + (g.pos[u] - g.pos[n]).norm());
        CHECK(r.bt[u] < bt);  // no local minima: the parent burned earlier
      }
    CHECK(primes >= 1);
    CHECK(best == Approx(bt).epsilon(1e-12).margin(1e-12));
    // The sectors with a primary arc form an exposing set: the other sectors leave H_v acyclic.
    if (g.is_vertex(n)) {
      std::vector<int> parent(g.vsec.h_nodes[n]);
      std::iota(parent.begin(), parent.end(), 0);
      std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
      bool acyclic = true;
      for (Index s = g.sector_begin[n]; s < g.sector_begin[n + 1]; ++s)
        if (r.prime_node[s] == kNone) {
          const int a = find(g.vsec.end_a[s]), b = find(g.vsec.end_b[s]);
          if (a == b) acyclic = false;
          else parent[a] = b;
        }
      CHECK(acyclic);
    } else {
      CHECK(g.sector_begin[n + 1] - g.sector_begin[n] - primes <= 1);  // k parallel sectors: one may stay
    }
  }
}

}  // namespace

TEST_CASE("Rounded plate: BT is R plus the distance to the rim and the error shrinks with omega") {
  const double w = 1.0, h = 0.6, r = 0.05;
  MedialComplex mc = make_plate(w, h, 10, 6, fx::constant_radius(r));
  // Jitter the vertices (along the rim for rim vertices) so that no graph path is exact by luck.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  for (Vec3& p : mc.centres) {
    const bool rim_x = p.x() < 1e-9 || p.x() > w - 1e-9, rim_y = p.y() < 1e-9 || p.y() > h - 1e-9;
    if (!rim_x) p.x() += jitter(rng);
    if (!rim_y) p.y() += jitter(rng);
  }
  std::vector<double> errors;
  for (double omega : {0.1, 0.05, 0.02, 0.01, 0.005}) {
    const Burned b = burn_complex(mc, omega);
    const double err = max_error(b, [&](const Vec3& p) { return r + plate_exact_distance(p, w, h); });
    INFO("omega " << omega << " max error " << err);
    CHECK(err < 0.02);
    errors.push_back(err);
    check_invariants(b);
    // ET peaks at min(W, H) / 2 in the middle.
    double peak = 0;
    for (Index n = 0; n < b.g().num_nodes(); ++n) peak = std::max(peak, b.r().bt[n] - b.g().radius[n]);
    CHECK(peak >= std::min(w, h) / 2 - 0.03);  // the mid-line is sampled only where nodes fall on it
    CHECK(peak <= std::min(w, h) / 2 + err + 1e-9);
  }
  WARN("max BT_G - BT by omega 0.1 .. 0.005: " << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3] << " " << errors[4]);
  CHECK(errors.back() < 0.5 * errors.front());
  CHECK(errors.back() < 0.003);
}

TEST_CASE("Rounded plate with zero radius: BT is the distance to the rim") {
  const MedialComplex mc = make_plate(1.0, 1.0, 8, 8, fx::constant_radius(0.0));
  const Burned b = burn_complex(mc, 0.02);
  const double err = max_error(b, [](const Vec3& p) { return plate_exact_distance(p, 1, 1); });
  CHECK(err < 0.01);
  check_invariants(b);
}

TEST_CASE("Three-page book: seam and page burn times match the notes") {
  const double L = 10, a = 1, bh = 3, r = 0.5;
  const MedialComplex mc = make_book(L, a, bh, r, 40, 4);
  const Burned b = burn_complex(mc, 0.1);
  const BurnGraph& g = b.g();
  double worst = 0;
  double ridge = 0;
  for (Index n = 0; n < g.num_nodes(); ++n) {
    const Vec3& p = g.pos[n];
    const double u = p.x();
    double exact;
    if (p.tail<2>().norm() < 1e-9) {
      exact = r + std::min({a, u, L - u});
    } else {
      const Vec3 d = Vec3(0, p.y(), p.z()).normalized();
      const double v = p.tail<2>().norm();
      const bool page3 = (d - fx::book_direction(2)).norm() < 1e-6;
      exact = page3 ? r + std::min({bh - v, u, L - u, a + v}) : r + std::min({a - v, u, L - u});
      if (page3 && std::abs(u - L / 2) < 1) ridge = std::max(ridge, b.r().bt[n] - r);
    }
    REQUIRE(b.r().bt[n] >= exact - 1e-9);
    worst = std::max(worst, b.r().bt[n] - exact);
  }
  INFO("max error " << worst);
  CHECK(worst < 0.05);
  // The seam in the middle burns at r + a = 1.5; page 3's ridge is at ET = (b + a)/2 = 2.
  for (Index n = 0; n < g.num_nodes(); ++n)
    if (g.pos[n].tail<2>().norm() < 1e-9 && std::abs(g.pos[n].x() - L / 2) < 1e-9) CHECK(b.r().bt[n] == Approx(1.5));
  CHECK(ridge >= 2.0 - 1e-9);
  CHECK(ridge <= 2.0 + worst);
  check_invariants(b);
}

TEST_CASE("Varying Lipschitz radius: invariants hold and rigid motions and scaling act on BT as they should") {
  auto radius = [](const Vec3& p) { return 0.1 + 0.3 * std::sin(3 * p.x()) * std::cos(2 * p.y()) * 0.5 + 0.15; };
  const MedialComplex mc = make_book(2.0, 0.7, 1.3, 0.0, 16, 8);
  MedialComplex varied = mc;
  for (std::size_t v = 0; v < varied.num_vertices(); ++v) varied.radii[v] = radius(varied.centres[v]);
  const Burned b = burn_complex(varied, 0.03);
  check_invariants(b);

  // Rigid motions do not change BT (up to round-off).
  MedialComplex rotated = varied;
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : rotated.centres) p = rot * p + Vec3(0.3, 0.1, -2);
  const Burned rb = burn_complex(rotated, 0.03);
  REQUIRE(rb.g().num_nodes() == b.g().num_nodes());
  for (Index n = 0; n < b.g().num_nodes(); ++n) CHECK(rb.r().bt[n] == Approx(b.r().bt[n]).epsilon(1e-9));

  MedialComplex scaled = varied;
  scaled.transform({2.5, Vec3(1, -2, 3)});
  const Burned c = burn_complex(scaled, 0.03 * 2.5);
  REQUIRE(c.g().num_nodes() == b.g().num_nodes());
  for (Index n = 0; n < b.g().num_nodes(); ++n) CHECK(c.r().bt[n] == Approx(2.5 * b.r().bt[n]).epsilon(1e-9));
}

TEST_CASE("BT is infinite exactly on closed surfaces") {
  // A plate, a separate closed sphere, and a sphere with a fin: only sphere nodes never burn.
  MedialComplex mc = make_plate(1.0, 1.0, 4, 4, fx::constant_radius(0.1));
  const Index plate_vertices = static_cast<Index>(mc.num_vertices());
  fx::add_sphere(mc, Vec3(3, 0, 0), 0.5, 3, 0.1);
  const Index sphere_end = static_cast<Index>(mc.num_vertices());
  // Fin on the second sphere: a page glued to its equator vertices would need exact positions;
  // instead, a fin page whose bottom edge is an edge of the sphere mesh.
  fx::add_sphere(mc, Vec3(6, 0, 0), 0.5, 2, 0.1);
  const Index fin_a = sphere_end, fin_b = sphere_end + 1;  // first two vertices of that sphere: an edge
  const Vec3 up(0, 0, 1);
  const Index top_a = mc.add_vertex(mc.centres[fin_a] + up, 0.1), top_b = mc.add_vertex(mc.centres[fin_b] + up, 0.1);
  mc.add_face(fin_a, fin_b, top_b);
  mc.add_face(fin_a, top_b, top_a);
  mc.close_edges();
  const Burned b = burn_complex(mc, 0.05);
  const BurnGraph& g = b.g();
  const Index V = g.num_vertices();
  for (Index v = 0; v < V; ++v) {
    const bool on_sphere = v >= plate_vertices && v < top_a;
    INFO("vertex " << v);
    CHECK(std::isinf(b.r().bt[v]) == on_sphere);
  }
  // Samples: infinite iff their edge is a sphere edge.
  for (Index n = V; n < g.num_nodes(); ++n) {
    const Segment& e = g.cx->edges[g.sample_edge[n - V]];
    const bool on_sphere = e[0] >= plate_vertices && e[0] < top_a && e[1] >= plate_vertices && e[1] < top_a;
    CHECK(std::isinf(b.r().bt[n]) == on_sphere);
  }
  check_invariants(b);
}

TEST_CASE("Box medial axis: BT converges to a fine-omega reference") {
  // The paper's accuracy test (Fig. 11) uses the analytic medial axis of a box; here the
  // interior-Voronoi complex of a (jittered) box mesh, against omega = 0.0005 as the reference
  // (the notes §9.5: the paper gives no closed form).
  SurfaceMesh box = medax::testing::make_box(0.5, 0.35, 0.2, 8);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1e-4, 1e-4);
  for (Vec3& p : box.vertices) p += Vec3(u(rng), u(rng), u(rng));
  MedialComplex mc = fx::interior_voronoi_complex(box);
  make_pure_complex(mc, 1e-9);
  const Burned reference = burn_complex(mc, 0.0005);
  std::vector<double> errors;
  for (double omega : {0.032, 0.016, 0.008, 0.004, 0.002}) {
    const Burned b = burn_complex(mc, omega);
    double worst = 0;
    for (Index v = 0; v < b.g().num_vertices(); ++v) {
      const double ref = reference.r().bt[v];
      if (ref > 0.01) worst = std::max(worst, b.r().bt[v] / ref - 1);
    }
    errors.push_back(worst);
  }
  WARN("box: max BT(omega) / BT(0.0005) - 1 over the vertices, omega 0.032 .. 0.002: "
       << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3] << " " << errors[4]);
  CHECK(errors[3] < 0.05);
  CHECK(errors[4] <= errors[0]);
}

TEST_CASE("Burn arcs never cross inside a triangle") {
  const MedialComplex book = make_book(4.0, 1.0, 2.0, 0.2, 12, 3);
  for (double omega : {0.3, 0.1, 0.05}) {
    const Burned b = burn_complex(book, omega);
    const Subdivision sub = build_subdivision(b.g(), b.r());
    CHECK(sub.crossing_arcs == 0);
    CHECK(sub.unconnected_faces == 0);
  }
}

TEST_CASE("1D burn equals brute force Eq. 1 on random trees") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    Graph1D tree;
    const int n = 2 + trial;
    for (int i = 0; i < n; ++i) {
      tree.points.push_back(Vec3(unit(rng), unit(rng), unit(rng)) * 3);
      if (i > 0) tree.edges.push_back({Index(std::uniform_int_distribution<int>(0, i - 1)(rng)), Index(i)});
    }
    // 1-Lipschitz ignition times (Euclidean, hence along the tree too).
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    for (const Vec3& p : tree.points) tree.ignite.push_back(2 + 0.9 * dir.dot(p) * 0.3);
    const auto fast = burn_1d(tree), slow = burn_1d_brute_force(tree);
    for (int i = 0; i < n; ++i) CHECK(fast[i] == Approx(slow[i]).epsilon(1e-12));
  }
}

TEST_CASE("1D burn: cycles never burn and junctions burn at their second-to-last arrival") {
  Graph1D g;
  // A triangle cycle 0-1-2 with a tail 2-3-4.
  g.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(0, 3, 0)};
  g.edges = {{0, 1}, {1, 2}, {2, 0}, {2, 3}, {3, 4}};
  g.ignite = {0, 0, 0, 0, 0.5};
  const auto bt = burn_1d(g);
  CHECK(std::isinf(bt[0]));
  CHECK(std::isinf(bt[1]));
  CHECK(std::isinf(bt[2]));
  CHECK(bt[4] == Approx(0.5));
  CHECK(bt[3] == Approx(1.5));
  // A star: three legs of lengths 1, 2, 3, ignition 0: the centre burns at 2.
  Graph1D star;
  star.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3)};
  star.edges = {{0, 1}, {0, 2}, {0, 3}};
  star.ignite = {0, 0, 0, 0};
  CHECK(burn_1d(star)[0] == Approx(2.0));
}
