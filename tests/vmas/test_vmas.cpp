// VMAS (plugins/vmas): the properties of docs/notes/huang2024_vmas.md §5 on analytic
// shapes, the solver's edit API, the edit scripts, both stages (mesh and point cloud) and the
// package in a pipeline.
#include "pipeline_run.hpp"
#include "edits.hpp"
#include "energy.hpp"
#include "partition.hpp"
#include "stages.hpp"
#include "vmas.hpp"

#include <medax/io.hpp>
#include <medax/kernel/pipeline.hpp>
#include <medax/kernel/registry.hpp>
#include <medax/kernel/runner.hpp>
#include <medax/services/closest_point.hpp>
#include <medax/services/inside.hpp>
#include <medax/services/sampling.hpp>
#include <medax/testing/shapes.hpp>
#include <medax/union_find.hpp>
#include <test_paths.hpp>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>

using namespace medax;
using namespace medax::vmas;

namespace {

/// A star-shaped blob without symmetries (so no split decision is a tie).
SurfaceMesh make_blob(int subdivisions = 4) {
  SurfaceMesh m = testing::make_sphere(1.0, subdivisions);
  for (Vec3& p : m.vertices) {
    const Vec3 u = p.normalized();
    const double r = 1.0 + 0.3 * std::sin(2.1 * u.x() + 0.4) * std::cos(1.3 * u.y() - 0.2) + 0.2 * u.z() * u.x() +
                     0.35 * std::max(0.0, u.x()) * std::max(0.0, u.x()) + 0.1 * u.y() * u.y() * u.z();
    p = u * r;
  }
  return m;
}

VmasOptions count_options(std::size_t target) {
  VmasOptions o;
  o.target_spheres = target;
  return o;
}

VmasSolver solve(const SurfaceMesh& mesh, const VmasOptions& o, const InputOptions& in = {}) {
  VmasSolver s(VmasInput::from_mesh(mesh, in), o);
  s.run();
  s.finish();
  return s;
}

double diagonal(const SurfaceMesh& m) { return bbox_diagonal(m.vertices); }

std::size_t components(std::size_t n, const std::vector<Segment>& edges, const std::vector<Tri>& faces) {
  UnionFind sets(n);
  for (const Segment& e : edges) sets.unite(e[0], e[1]);
  for (const Tri& f : faces) sets.unite(f[0], f[1]), sets.unite(f[1], f[2]);
  return sets.count();
}

/// b1 over Z/2 of the 2-complex (vertices, edges, triangles whose sides are all in `edges`).
std::size_t betti1(std::size_t n, const std::vector<Segment>& edges, const std::vector<Tri>& faces) {
  std::map<std::pair<Index, Index>, std::size_t> edge_index;
  for (const Segment& e : edges) edge_index.emplace(std::make_pair(std::min(e[0], e[1]), std::max(e[0], e[1])), edge_index.size());
  // rank ∂2 by Gaussian elimination over Z/2 on the triangles' edge sets.
  std::vector<std::vector<bool>> rows;
  for (const Tri& f : faces) {
    std::vector<bool> row(edge_index.size(), false);
    for (int i = 0; i < 3; ++i) {
      const Index a = f[i], b = f[(i + 1) % 3];
      row[edge_index.at({std::min(a, b), std::max(a, b)})] = true;
    }
    rows.push_back(row);
  }
  std::size_t rank2 = 0;
  for (std::size_t col = 0; col < edge_index.size() && rank2 < rows.size(); ++col) {
    std::size_t pivot = rank2;
    while (pivot < rows.size() && !rows[pivot][col]) ++pivot;
    if (pivot == rows.size()) continue;
    std::swap(rows[pivot], rows[rank2]);
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (r != rank2 && rows[r][col])
        for (std::size_t k = 0; k < edge_index.size(); ++k) rows[r][k] = rows[r][k] != rows[rank2][k];
    ++rank2;
  }
  const std::size_t rank1 = n - components(n, edges, {});
  return edge_index.size() - rank1 - rank2;
}

std::vector<Sphere> local_spheres(const VmasSolver& s) {
  std::vector<Sphere> out;
  for (const SphereInfo& i : s.spheres()) out.push_back({i.centre - s.input().origin, i.radius});
  return out;
}

/// Runs a fresh vmas stage (at its defaults) with `changes` on `shape`.
MedialComplex run_stage(const Shape& shape, const std::map<std::string, ParamValue>& changes) {
  VmasStage stage;
  ParamSet params;
  for (const auto& [k, v] : changes) params.set(k, v);
  stage.configure(params);
  Scene scene;
  scene.shape = shape;
  stage.prepare(scene);
  BasicContext ctx(1);
  return stage.extract(shape, ctx);
}

void run_dual(MedialComplex& mc, const Shape& shape, const std::map<std::string, ParamValue>& changes = {}) {
  VmasDualStage dual;
  ParamSet params;
  for (const auto& [k, v] : changes) params.set(k, v);
  dual.configure(params);
  BasicContext ctx(1);
  dual.connect(shape, mc, ctx);
}

}  // namespace

TEST_CASE("vmas sphere: the first fit is the sphere itself") {
  const SurfaceMesh mesh = testing::make_sphere(1.0, 4);  // 2562 vertices
  REQUIRE(mesh.vertices.size() >= 2000);
  // From either first sphere (the largest shrinking ball, or the CGAL port's box corner with
  // radius = scale), with either Gauss-Newton steps, one iteration fits the sphere.
  for (const Correction c : {Correction::Off, Correction::Always})
    for (const GaussNewtonSteps steps : {GaussNewtonSteps::Guarded, GaussNewtonSteps::Raw})
      for (const InitialSphere start : {InitialSphere::LargestBall, InitialSphere::BoxCorner}) {
        VmasOptions o = count_options(1);
        o.correction = c;
        o.gn_steps = steps;
        o.initial_sphere = start;
        VmasSolver solver(VmasInput::from_mesh(mesh), o);
        if (start == InitialSphere::BoxCorner) {
          const SphereInfo s0 = solver.spheres()[0];
          CHECK((s0.centre - Vec3::Constant(-1.0)).norm() < 1e-9);
          CHECK(std::abs(s0.radius - 2.0) < 1e-9);
        }
        solver.iterate();
        REQUIRE(solver.size() == 1);
        const SphereInfo s = solver.spheres()[0];
        INFO("correction " << choice_name(kCorrections, c) << ", steps " << choice_name(kGaussNewtonSteps, steps)
                           << ", start " << choice_name(kInitialSpheres, start) << ": centre " << s.centre.transpose()
                           << " radius " << s.radius);
        CHECK(s.centre.norm() < 2e-3);
        CHECK(std::abs(s.radius - 1.0) < 2e-3);
      }
}

TEST_CASE("vmas capsule: centres on the axis and the skeleton is a path (shrinking balls on vertices or faces)") {
  const double rho = 0.2, half = 0.6;
  const SurfaceMesh mesh = testing::make_capsule(rho, half, 32);
  InputOptions in;
  in.sb_contacts = GENERATE(BallContacts::Vertices, BallContacts::Faces);
  const VmasSolver solver = solve(mesh, count_options(8), in);
  const MedialComplex mc = solver.complex(true);
  REQUIRE(mc.num_vertices() == 8);
  for (std::size_t i = 0; i < mc.num_vertices(); ++i) {
    INFO("sphere " << i << " at " << mc.centres[i].transpose() << " r " << mc.radii[i]);
    CHECK(testing::capsule_axis_distance(mc.centres[i], half) < 0.02 * diagonal(mesh));
    CHECK(std::abs(mc.radii[i] - rho) < 0.05 * rho);
  }
  CHECK(components(mc.num_vertices(), mc.edges, mc.faces) == 1);
  CHECK(mc.edges.size() == mc.num_vertices() - 1);
  CHECK(mc.faces.empty());
}

TEST_CASE("vmas shrinking balls on the vertices and on the faces: a sphere's balls") {
  // The only maximal ball of a sphere is the sphere. Balls through the vertices stop within the
  // tessellation's reach of it (< 4% of R here). The CGAL port's face balls stop earlier (the same
  // closest face twice ends them, though the ball may still shrink): each is an empty ball through
  // its surface point, at most 20% of R from the centre.
  const SurfaceMesh mesh = testing::make_sphere(1.0, 4);  // 2562 vertices, faces within 1.3e-3 of the sphere
  const services::SurfaceDistance distance(mesh);
  for (const BallContacts contacts : {BallContacts::Vertices, BallContacts::Faces}) {
    InputOptions in;
    in.sb_contacts = contacts;
    const auto input = VmasInput::from_mesh(mesh, in);
    const double reach = contacts == BallContacts::Vertices ? 0.04 : 0.2;
    const auto check_ball = [&](const Sphere& b) {
      const Vec3 centre = b.centre + input->origin;
      CHECK(centre.norm() < reach);
      CHECK(b.radius > 1.0 - reach);
      CHECK(b.radius <= distance.distance(centre) + 2.5e-3);  // empty, up to the faces' sagitta
    };
    INFO("sb_contacts " << choice_name(kBallContacts, contacts));
    for (std::size_t v = 0; v < mesh.vertices.size(); v += 97) {  // the split seeds SB[v]
      INFO("vertex " << v << ": centre " << input->vertex_balls[v].centre.transpose() << " r "
                     << input->vertex_balls[v].radius);
      check_ball(input->vertex_balls[v]);
    }
    // The correction of an off-centre sphere: the ball from its centre's closest surface point.
    const Sphere b = input->correct({Vec3(0.3, 0.1, -0.2) - input->origin, 0.4});
    INFO("corrected: centre " << b.centre.transpose() << " r " << b.radius);
    check_ball(b);
  }
}

TEST_CASE("vmas thick plate: centres on the mid-plane and triangles") {
  const double t = 0.2;
  const SurfaceMesh mesh = testing::make_box(1.0, 1.0, t / 2, 24);
  const VmasSolver solver = solve(mesh, count_options(20));
  const MedialComplex mc = solver.complex(true);
  REQUIRE(mc.num_vertices() == 20);
  std::size_t interior = 0;
  for (std::size_t i = 0; i < mc.num_vertices(); ++i) {
    const Vec3& c = mc.centres[i];
    INFO("sphere " << i << " at " << c.transpose() << " r " << mc.radii[i]);
    CHECK(std::abs(c.z()) < 0.01);
    if (std::abs(c.x()) < 1 - t && std::abs(c.y()) < 1 - t) {
      ++interior;
      CHECK(std::abs(mc.radii[i] - t / 2) < 0.01);
    }
  }
  CHECK(interior >= 4);
  CHECK(!mc.faces.empty());
}

TEST_CASE("vmas torus: the skeleton has a cycle") {
  const double R = 1.0;
  const SurfaceMesh mesh = testing::make_torus(R, 0.3, 64, 24);
  const VmasSolver solver = solve(mesh, count_options(12));
  const MedialComplex mc = solver.complex(true);
  REQUIRE(mc.num_vertices() >= 8);
  for (const Vec3& c : mc.centres) CHECK(testing::torus_axis_distance(c, R) < 0.02 * diagonal(mesh));
  CHECK(components(mc.num_vertices(), mc.edges, mc.faces) == 1);
  CHECK(betti1(mc.num_vertices(), mc.edges, mc.faces) >= 1);
}

TEST_CASE("vmas corrected spheres are inside and near-maximal") {
  const SurfaceMesh mesh = make_blob();
  const services::SurfaceDistance distance(mesh);
  const double tol = 1e-3 * diagonal(mesh);
  for (const SqemRows rows : {SqemRows::Paper, SqemRows::AuthorCode}) {
    VmasOptions o = count_options(24);
    o.sqem_rows = rows;
    const VmasSolver solver = solve(mesh, o);
    REQUIRE(solver.size() == 24);
    for (const SphereInfo& s : solver.spheres()) {
      const double d = distance.distance(s.centre);
      INFO((rows == SqemRows::Paper ? "paper" : "author_code") << " sphere " << s.id << " at " << s.centre.transpose()
                                                                << " r " << s.radius << ", distance to the surface " << d);
      CHECK(services::winding_number(mesh, s.centre) > 0.5);
      CHECK(s.radius <= d + tol);
      CHECK(s.radius >= 0.5 * d);
    }
  }
}

TEST_CASE("vmas energy never increases with correction off") {
  const SurfaceMesh mesh = make_blob();
  VmasOptions o = count_options(16);
  o.correction = Correction::Off;
  VmasSolver solver(VmasInput::from_mesh(mesh), o);
  const double rel = 1e-9;
  double previous = std::numeric_limits<double>::infinity();
  std::size_t checked = 0;
  solver.run([&](const IterationReport& r) {
    // Partition and update each never raise Σ E_v (while no sphere was added in between).
    CHECK(r.energy <= r.energy_partition * (1 + rel));
    if (std::isfinite(previous)) {
      CHECK(r.energy_partition <= previous * (1 + rel));
      ++checked;
    }
    previous = r.splits == 0 ? r.energy : std::numeric_limits<double>::infinity();
    return true;
  });
  const std::size_t count = solver.size();
  for (int i = 0; i < 15; ++i) {  // |M| fixed
    const IterationReport r = solver.relax();
    CHECK(r.energy_partition <= previous * (1 + rel));
    CHECK(r.energy <= r.energy_partition * (1 + rel));
    previous = r.energy;
    ++checked;
  }
  CHECK(solver.size() == count);
  CHECK(checked > 20);
}

TEST_CASE("vmas partition is the argmin of eq 8 and clusters have at least 4 vertices") {
  const SurfaceMesh mesh = make_blob();
  VmasSolver solver(VmasInput::from_mesh(mesh), count_options(20));
  solver.run();
  solver.relax();  // no split after it: every sphere has its cluster
  for (const SphereInfo& s : solver.spheres()) CHECK(s.cluster_size >= 4);

  const VmasInput& in = solver.input();
  const std::vector<Sphere> spheres = local_spheres(solver);
  std::vector<int> cluster_of;
  assign_vertices(in, spheres, 0.2, cluster_of);
  std::size_t wrong = 0;
  for (Index v = 0; v < in.size(); ++v) {
    REQUIRE(cluster_of[v] >= 0);
    const double chosen = vertex_energy(in, v, spheres[static_cast<std::size_t>(cluster_of[v])], 0.2);
    for (std::size_t j = 0; j < spheres.size(); ++j)
      if (vertex_energy(in, v, spheres[j], 0.2) < chosen) ++wrong;
  }
  CHECK(wrong == 0);
  // The hint only prunes: any hint, stale or out of range, gives the same partition.
  std::vector<int> hinted, garbage(in.size());
  for (Index v = 0; v < in.size(); ++v) garbage[v] = static_cast<int>((v * 7919) % (spheres.size() + 3)) - 1;
  assign_vertices(in, spheres, 0.2, hinted, &solver.assignment());
  CHECK(hinted == cluster_of);
  assign_vertices(in, spheres, 0.2, hinted, &garbage);
  CHECK(hinted == cluster_of);
}

TEST_CASE("vmas partition with the CGAL port's vertex-normal SQEM is the argmin of its energy") {
  // partition_sqem: vertex_normal: E_v = A(v)·((v − q)·n_v − r)² + λ·A(v)·(|v − q| − r)².
  const SurfaceMesh mesh = make_blob();
  VmasOptions o = count_options(20);
  o.partition_sqem = PartitionSqem::VertexNormal;
  VmasSolver solver(VmasInput::from_mesh(mesh), o);
  solver.run();
  CHECK(solver.size() == 20);
  const VmasInput& in = solver.input();
  const std::vector<Sphere> spheres = local_spheres(solver);
  const auto energy = [&](Index v, const Sphere& s) {
    const double plane = (in.points[v] - s.centre).dot(in.normals[v]) - s.radius;
    const double eucl = (in.points[v] - s.centre).norm() - s.radius;
    return in.areas[v] * (plane * plane + 0.2 * eucl * eucl);
  };
  // The cluster errors (eq. 12) use it: against the current spheres, over the last partition.
  std::vector<double> sum(spheres.size(), 0.0), area(spheres.size(), 0.0);
  for (Index v = 0; v < in.size(); ++v) {
    const int c = solver.assignment()[v];
    REQUIRE(c >= 0);
    sum[static_cast<std::size_t>(c)] += energy(v, spheres[static_cast<std::size_t>(c)]);
    area[static_cast<std::size_t>(c)] += in.areas[v];
  }
  const std::vector<SphereInfo> info = solver.spheres();
  for (std::size_t i = 0; i < spheres.size(); ++i) CHECK(info[i].error == Approx(sum[i] / area[i]).epsilon(1e-9));
  // The partition is its argmin.
  const std::vector<PackedQuadric> quadrics = vertex_normal_quadrics(in);
  std::vector<int> normal, diffused;
  assign_vertices(in, spheres, 0.2, normal, nullptr, &quadrics);
  assign_vertices(in, spheres, 0.2, diffused);
  std::size_t wrong = 0, differs_from_diffused = 0;
  for (Index v = 0; v < in.size(); ++v) {
    const double chosen = energy(v, spheres[static_cast<std::size_t>(normal[v])]);
    for (const Sphere& s : spheres)
      if (energy(v, s) < chosen * (1 - 1e-9) - 1e-15) ++wrong;
    differs_from_diffused += normal[v] != diffused[v];
  }
  CHECK(wrong == 0);
  CHECK(differs_from_diffused > 0);  // the two energies are not the same partition
}

TEST_CASE("vmas incremental partition equals the full argmin") {
  const SurfaceMesh mesh = make_blob();
  VmasSolver solver(VmasInput::from_mesh(mesh), count_options(20));
  solver.run();
  const VmasInput& in = solver.input();
  std::vector<Sphere> spheres = local_spheres(solver);
  std::vector<int> before;
  assign_vertices(in, spheres, 0.2, before);
  // Move a few spheres (one of them onto another's exact values: a tie), add one, then update.
  std::vector<char> moved(spheres.size(), 0);
  for (const std::size_t j : {std::size_t{2}, std::size_t{7}, std::size_t{11}}) {
    spheres[j].centre += Vec3(0.03, -0.02, 0.01) * static_cast<double>(j % 3 + 1);
    spheres[j].radius *= 1.05;
    moved[j] = 1;
  }
  spheres[15] = spheres[4], moved[15] = 1;
  spheres.push_back(in.vertex_balls[in.nearest_vertex(Vec3(0.5, 0.2, 0.1))]), moved.push_back(1);
  std::vector<int> incremental = before, full;
  reassign_vertices(in, spheres, 0.2, moved, incremental);
  assign_vertices(in, spheres, 0.2, full);
  CHECK(incremental == full);
  CHECK(incremental != before);
  // Nothing moved: nothing changes.
  std::vector<int> same = full;
  reassign_vertices(in, spheres, 0.2, std::vector<char>(spheres.size(), 0), same);
  CHECK(same == full);
}

TEST_CASE("vmas local update keeps the partition at the argmin through splits, edits and relaxation") {
  const SurfaceMesh mesh = make_blob();
  VmasSolver solver(VmasInput::from_mesh(mesh), count_options(24));
  REQUIRE(solver.options().update_scope == UpdateScope::Local);
  // After an edit the spheres and the partition belong together (nothing was updated since),
  // so the solver's incremental partition must be the brute-force argmin of eq. 8.
  const auto check_argmin = [&] {
    const VmasInput& in = solver.input();
    const std::vector<Sphere> spheres = local_spheres(solver);
    std::size_t wrong = 0;
    for (Index v = 0; v < in.size(); ++v) {
      const int c = solver.assignment()[v];
      if (c < 0) continue;
      const double chosen = vertex_energy(in, v, spheres[static_cast<std::size_t>(c)], 0.2);
      for (std::size_t j = 0; j < spheres.size(); ++j) {
        const double e = vertex_energy(in, v, spheres[j], 0.2);
        if (e < chosen || (e == chosen && j < static_cast<std::size_t>(c))) ++wrong;
      }
    }
    std::vector<int> full;
    assign_vertices(in, spheres, 0.2, full);
    CHECK(wrong == 0);
    CHECK(full == solver.assignment());
  };
  for (int i = 0; i < 12; ++i) solver.iterate();
  solver.split_sphere(solver.nearest_sphere(Vec3(1, 0, 0)));
  check_argmin();
  solver.run();
  solver.split_sphere(solver.nearest_sphere(Vec3(0, 1, 0)));
  check_argmin();
  for (int i = 0; i < 5; ++i) solver.relax();
  solver.remove_sphere(solver.nearest_sphere(Vec3(0, 0, 1)));
  check_argmin();
  for (int i = 0; i < 5; ++i) solver.relax();
  solver.add_sphere(solver.input().nearest_vertex(Vec3(-1, 0, 0) - solver.input().origin));
  check_argmin();
}

TEST_CASE("vmas local and full updates reach the same optimum") {
  // The local scope only skips updates that would repeat a converged solve on an unchanged
  // cluster: same count, and the same energy up to the drift of a converged state.
  const SurfaceMesh mesh = make_blob();
  VmasOptions full = count_options(30), local = full;
  full.update_scope = UpdateScope::Full;
  const VmasSolver a = solve(mesh, local), b = solve(mesh, full);
  CHECK(a.size() == b.size());
  CHECK(a.last_report().total_error == Approx(b.last_report().total_error).epsilon(0.05));
  // A settled sphere is not touched again: relaxing a converged local state moves at most the
  // spheres whose clusters still change, and never changes the count.
  VmasSolver c = a;
  const std::vector<SphereInfo> before = c.spheres();
  for (int i = 0; i < 5; ++i) c.relax();
  CHECK(c.size() == a.size());
  std::size_t unchanged = 0;
  for (const SphereInfo& s : before) unchanged += c.sphere(s.id).centre == s.centre;
  CHECK(unchanged > 0);
}

TEST_CASE("vmas dual: connected input gives a connected skeleton whose edges are the touching clusters") {
  const SurfaceMesh mesh = make_blob();
  const VmasSolver solver = solve(mesh, count_options(25));
  const MedialComplex mc = solver.complex(true, TriangleRule::Cliques);
  CHECK(components(mc.num_vertices(), mc.edges, mc.faces) == 1);
  std::set<std::pair<Index, Index>> edges;
  for (const Segment& e : mc.edges) edges.insert({e[0], e[1]});
  for (const Tri& f : mc.faces) {
    CHECK(edges.count({f[0], f[1]}));
    CHECK(edges.count({f[1], f[2]}));
    CHECK(edges.count({f[0], f[2]}));
  }
  // An edge exists exactly where some mesh edge joins the two clusters.
  const std::vector<int>& cl = solver.assignment();
  std::set<std::pair<Index, Index>> touching;
  for (const Tri& f : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      const int a = cl[f[i]], b = cl[f[(i + 1) % 3]];
      if (a >= 0 && b >= 0 && a != b)
        touching.insert({static_cast<Index>(std::min(a, b)), static_cast<Index>(std::max(a, b))});
    }
  CHECK(touching == edges);
  // Restricted triangles are cliques realised by a surface triangle.
  const MedialComplex restricted = solver.complex(true, TriangleRule::Restricted);
  std::set<Tri> cliques(mc.faces.begin(), mc.faces.end());
  for (const Tri& f : restricted.faces) CHECK(cliques.count(f));
  CHECK(restricted.faces.size() <= mc.faces.size());
}

TEST_CASE("vmas count mode stops at the target") {
  for (const std::size_t target : {std::size_t{10}, std::size_t{31}}) {
    const VmasSolver solver = solve(make_blob(), count_options(target));
    CHECK(solver.size() == target);
    CHECK(solver.last_report().stop);
    CHECK(solver.last_report().converged);
    CHECK(solver.iterations() < solver.options().max_iterations);
  }
}

TEST_CASE("vmas stop_test after_split ends at the target, no later than before_split") {
  // Both runs make the same decisions until the CGoGN code's test (after the split round) stops
  // the after_split run: on a round made on convergence that reaches the target, its new
  // spheres unoptimised.
  bool stopped_on_a_split = false;
  for (const std::size_t target : {std::size_t{10}, std::size_t{23}, std::size_t{31}}) {
    VmasOptions o = count_options(target);
    const VmasSolver before = solve(make_blob(), o);
    o.stop_test = StopTest::AfterSplit;
    const VmasSolver after = solve(make_blob(), o);
    INFO("target " << target);
    CHECK(after.size() == target);
    CHECK(after.last_report().stop);
    CHECK(after.last_report().converged);
    CHECK(after.iterations() <= before.iterations());
    if (after.last_report().splits > 0) {
      stopped_on_a_split = true;
      CHECK(after.iterations() < before.iterations());
    } else {
      CHECK(after.iterations() == before.iterations());
    }
  }
  CHECK(stopped_on_a_split);
}

TEST_CASE("vmas stops when a too-coarse mesh cannot hold the target") {
  // 162 vertices cannot give 60 clusters of ≥ 4 vertices each for long: new spheres keep being
  // culled, so the run stalls and stops long before max_iterations.
  const VmasSolver solver = solve(testing::make_sphere(1.0, 2), count_options(60));
  CHECK(solver.last_report().stalled);
  CHECK(solver.last_report().stop);
  CHECK(solver.size() < 60);
  CHECK(solver.iterations() < 400);
}

TEST_CASE("vmas error mode stops below the threshold") {
  const SurfaceMesh mesh = make_blob();
  std::size_t previous = 0;
  for (const double threshold : {2e-3, 5e-4}) {
    VmasOptions o;
    o.stop_mode = StopMode::Error;
    o.error_threshold = threshold;
    const VmasSolver solver = solve(mesh, o);
    const double s2 = solver.input().scale * solver.input().scale;
    const IterationReport& r = solver.last_report();
    INFO("threshold " << threshold << ": " << solver.size() << " spheres, max error " << r.max_error / s2);
    CHECK(r.stop);
    CHECK(r.converged);
    CHECK(r.max_error < threshold * s2);
    CHECK(solver.size() > previous);  // a lower threshold gives more spheres
    previous = solver.size();
  }
}

TEST_CASE("vmas is scale invariant") {
  const SurfaceMesh mesh = make_blob();
  // Splits on the fixed schedule only, so that no decision hinges on a threshold (see the
  // rigid-motion case); thresholds are relative to the scale anyway.
  VmasOptions o = count_options(20);
  o.converge_eps = 0;
  o.split_period = 4;
  o.max_iterations = 60;
  const VmasSolver a = solve(mesh, o);
  for (const double sigma : {2.0, 1.7}) {
    SurfaceMesh scaled = mesh;
    for (Vec3& p : scaled.vertices) p *= sigma;
    const VmasSolver b = solve(scaled, o);
    REQUIRE(a.size() == b.size());
    const auto sa = a.spheres(), sb = b.spheres();
    const double tol = sigma == 2.0 ? 1e-12 : 1e-6;  // a power of two scales every float exactly
    for (std::size_t i = 0; i < sa.size(); ++i) {
      CHECK((sa[i].centre * sigma - sb[i].centre).norm() <= tol * sigma);
      CHECK(std::abs(sa[i].radius * sigma - sb[i].radius) <= tol * sigma);
    }
    CHECK(a.assignment() == b.assignment());
  }
}

TEST_CASE("vmas commutes with rigid motions") {
  const SurfaceMesh mesh = make_blob();
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-1.1, Vec3::UnitZ())).toRotationMatrix();
  const Vec3 t(3.5, -1.25, 10.0);
  SurfaceMesh moved = mesh;
  for (Vec3& p : moved.vertices) p = R * p + t;
  SECTION("step by step, when no decision hinges on a threshold") {
    // Splits on the fixed schedule only (no convergence test): every decision is a comparison
    // of clearly different values, so the two runs stay together up to round-off.
    VmasOptions o = count_options(20);
    o.converge_eps = 0;
    o.split_period = 4;
    o.max_iterations = 60;
    const VmasSolver a = solve(mesh, o), b = solve(moved, o);
    REQUIRE(a.size() == 20);
    REQUIRE(b.size() == 20);
    const auto sa = a.spheres(), sb = b.spheres();
    for (std::size_t i = 0; i < sa.size(); ++i) {
      CHECK((R * sa[i].centre + t - sb[i].centre).norm() < 1e-6);
      CHECK(std::abs(sa[i].radius - sb[i].radius) < 1e-6);
    }
    CHECK(a.assignment() == b.assignment());
  }
  SECTION("with the defaults") {
    // The convergence test |ΔE_tot| < ε is a threshold: round-off can move a split round by an
    // iteration, and the run then settles in a different local minimum of the same quality.
    const VmasSolver a = solve(mesh, count_options(20)), b = solve(moved, count_options(20));
    CHECK(a.size() == b.size());
    CHECK(std::abs(a.last_report().total_error - b.last_report().total_error) < 0.05 * a.last_report().total_error);
  }
}

TEST_CASE("vmas gives identical results across thread counts") {
  const SurfaceMesh mesh = make_blob();
  // The defaults, and the authors' choices together (each a different code path).
  VmasOptions authors = count_options(30);
  authors.gn_steps = GaussNewtonSteps::Raw;
  authors.partition_sqem = PartitionSqem::VertexNormal;
  authors.stop_test = StopTest::AfterSplit;
  authors.initial_sphere = InitialSphere::BoxCorner;
  authors.sqem_rows = SqemRows::AuthorCode;
  InputOptions faces;  // and the CGAL port's shrinking ball
  faces.sb_contacts = BallContacts::Faces;
  faces.sb_angle_deg = 30;
  for (const auto& [options, in] : {std::make_pair(count_options(30), InputOptions{}), std::make_pair(authors, faces)}) {
    const auto run_with = [&](int threads) {
      // global_control caps the threads; an arena of that size makes TBB use them even on a
      // machine with fewer cores.
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      tbb::task_arena arena(threads);
      return arena.execute([&] {
        const VmasSolver s = solve(mesh, options, in);
        return std::make_pair(s.complex(true), s.assignment());
      });
    };
    const auto one = run_with(1);
    for (const int threads : {2, 4}) {
      const auto many = run_with(threads);
      CHECK(one.first.centres == many.first.centres);
      CHECK(one.first.radii == many.first.radii);
      CHECK(one.first.edges == many.first.edges);
      CHECK(one.first.faces == many.first.faces);
      CHECK(one.second == many.second);
    }
  }
}

TEST_CASE("vmas edits: split and remove change the count by one and the skeleton only locally") {
  // A long capsule: the far end is a chain of clusters away from the edit. Locality is measured
  // against the same solver continuing without the edit (a converged state still drifts a little),
  // with both update scopes: beyond 1.5 (≈ 4 spheres along the axis) nothing moves.
  const double half = 2.0;
  const SurfaceMesh mesh = testing::make_capsule(0.2, half, 24);
  VmasOptions options = count_options(14);
  options.update_scope = GENERATE(UpdateScope::Local, UpdateScope::Full);
  VmasSolver solver = solve(mesh, options);
  REQUIRE(solver.size() == 14);
  VmasSolver control = solver;
  const auto relax_both = [&](int n) {
    for (int i = 0; i < n; ++i) solver.relax(), control.relax();
  };
  // Largest change against the control, among the spheres farther than `radius` from `at`, and
  // among all of them.
  const auto changes = [&](const Vec3& at, double radius) {
    double far = 0, any = 0;
    for (const SphereInfo& s : control.spheres()) {
      if (!solver.contains(s.id)) continue;
      const double d = (solver.sphere(s.id).centre - s.centre).norm();
      any = std::max(any, d);
      if ((s.centre - at).norm() > radius) far = std::max(far, d);
    }
    return std::make_pair(far, any);
  };

  SECTION("split") {
    const Vec3 at(0, 0, half);
    const SphereId target = solver.nearest_sphere(at);
    const SphereId added = solver.split_sphere(target);
    CHECK(solver.size() == 15);
    CHECK(solver.contains(added));
    CHECK(solver.contains(target));
    relax_both(10);
    CHECK(solver.size() == 15);
    CHECK(solver.contains(added));
    const auto [far, any] = changes(at, 1.5);
    CHECK(any > 1e-3);    // the neighbourhood made room for the new sphere ...
    CHECK(far < 1e-9);    // ... and nothing beyond it changed
    // Continuing with the automatic schedule keeps the count (the target is met).
    solver.run();
    CHECK(solver.size() == 15);
  }
  SECTION("remove") {
    const Vec3 at(0, 0, -half);
    const SphereId target = solver.nearest_sphere(at);
    solver.remove_sphere(target);
    CHECK(solver.size() == 13);
    CHECK_FALSE(solver.contains(target));
    relax_both(10);
    CHECK(solver.size() == 13);
    const auto [far, any] = changes(at, 1.5);
    CHECK(any > 1e-3);
    CHECK(far < 1e-9);
    // The skeleton is still a path.
    const MedialComplex mc = solver.complex(true);
    CHECK(mc.edges.size() == 12);
    CHECK(components(mc.num_vertices(), mc.edges, mc.faces) == 1);
    // The automatic schedule refills up to the target.
    solver.run();
    CHECK(solver.size() == 14);
  }
  SECTION("add") {
    const SphereId added = solver.add_sphere(solver.input().nearest_vertex(Vec3(0.2, 0, 0) - solver.input().origin));
    CHECK(solver.size() == 15);
    CHECK(solver.contains(added));
  }
}

TEST_CASE("vmas edit scripts parse in order and refuse mistakes") {
  const auto edits = parse_edits("split 0.1 0.2 0.3 after 5; remove [1, 2, 3]\n- add (0, 0, -1) after 2 # comment\n\n");
  REQUIRE(edits.size() == 3);
  CHECK(edits[0].op == EditOp::Add);
  CHECK(edits[0].after == 2);
  CHECK(edits[0].point == Vec3(0, 0, -1));
  CHECK(edits[1].op == EditOp::Split);
  CHECK(edits[1].after == 5);
  CHECK(edits[1].point == Vec3(0.1, 0.2, 0.3));
  CHECK(edits[2].op == EditOp::Remove);
  CHECK(edits[2].after == Edit::kEnd);
  CHECK(parse_edits("").empty());
  CHECK(parse_edits("split 1 2 3 after end")[0].after == Edit::kEnd);
  CHECK_THROWS_WITH(parse_edits("split 1 2"), Catch::Contains("three coordinates"));
  CHECK_THROWS_WITH(parse_edits("explode 1 2 3"), Catch::Contains("unknown operation 'explode'"));
  CHECK_THROWS_WITH(parse_edits("split 1 2 x"), Catch::Contains("'x' is not a number"));
  CHECK_THROWS_WITH(parse_edits("split 1 2 3 after soon"), Catch::Contains("'soon'"));
  CHECK_THROWS_WITH(parse_edits("split 1 2 3 before 4"), Catch::Contains("unexpected 'before'"));
}

TEST_CASE("vmas stage applies scripted edits in the input frame") {
  Shape shape;
  shape.mesh = testing::make_capsule(0.2, 1.0, 24);
  // The shape has been moved by a conditioning stage: edits are given in the input's frame.
  shape.to_input = {2.0, Vec3(1, 0, 0)};
  for (Vec3& p : shape.mesh.vertices) p = (p - Vec3(1, 0, 0)) / 2.0;
  const auto ends = "remove 1 0 2.4 after end; split 1 0 -2.4 after end\nsplit 1 0 0 after end";
  MedialComplex mc = run_stage(shape, {{"target_spheres", 8LL}, {"edits", std::string(ends)}});
  CHECK(mc.num_vertices() == 9);  // 8 − 1 + 2, then relaxation without splits
  CHECK(mc.generators.size() == 9);
  CHECK(mc.generator_kind == "mesh_vertex");
  CHECK(mc.has(kVmasError));
  CHECK(mc.has(kVmasArea));
  CHECK(mc.get(kVmasId).size() == 9);
  // An edit during the run: the schedule refills up to the target.
  mc = run_stage(shape, {{"target_spheres", 8LL}, {"edits", std::string("remove 1 0 0 after 25")}});
  CHECK(mc.num_vertices() == 8);
  // A bad script is refused when the pipeline is validated, before any work.
  VmasStage stage;
  ParamSet bad;
  bad.set("edits", std::string("split 1 2"));
  stage.configure(bad);
  CHECK_THROWS_WITH(stage.check_params(), Catch::Contains("edit 'split 1 2': needs three coordinates"));
}

TEST_CASE("vmas stages on an oriented point cloud") {
  const double half = 0.6;
  const SurfaceMesh mesh = testing::make_capsule(0.2, half, 32);
  Shape shape;
  shape.samples = services::vertex_samples(mesh);
  MedialComplex mc = run_stage(shape, {{"target_spheres", 8LL}});
  REQUIRE(mc.num_vertices() == 8);
  CHECK(mc.generator_kind == "sample");
  for (const Vec3& c : mc.centres) CHECK(testing::capsule_axis_distance(c, half) < 0.03 * diagonal(mesh));
  run_dual(mc, shape);
  CHECK(components(mc.num_vertices(), mc.edges, mc.faces) == 1);
  CHECK(mc.edges.size() == 7);
  // No samples and no mesh: refused before any work.
  Scene empty;
  CHECK_THROWS_WITH(VmasStage().prepare(empty), Catch::Contains("sample"));
}

TEST_CASE("vmas_dual recomputes the clusters of spheres that carry none") {
  Shape shape;
  shape.mesh = make_blob();
  MedialComplex mc = run_stage(shape, {{"target_spheres", 15LL}});
  MedialComplex with = mc;
  run_dual(with, shape);
  MedialComplex without = mc;
  without.generators.clear();
  without.generator_kind.clear();
  run_dual(without, shape);
  CHECK(without.generators.size() == 15);
  CHECK(without.generator_kind == "mesh_vertex");
  CHECK(components(without.num_vertices(), without.edges, without.faces) == 1);
  CHECK(!with.edges.empty());
  // The clusters of the final spheres are those of the run, up to the last update.
  CHECK(std::abs(static_cast<double>(with.edges.size()) - static_cast<double>(without.edges.size())) <= 3);
  MedialComplex none = mc;
  run_dual(none, shape, {{"triangles", std::string("none")}});
  CHECK(none.faces.empty());
  CHECK(none.edges == with.edges);
}

TEST_CASE("vmas package runs in a pipeline") {
  Registry registry;
  REQUIRE(registry.load_file(MEDAX_VMAS_PLUGIN));
  for (const char* name : {"vmas", "vmas_dual"}) REQUIRE(registry.find(name));
  const auto dir = test::scratch_dir("vmas_pipeline");
  write_mesh(dir / "capsule.off", testing::make_capsule(0.2, 0.6, 24));
  const RunResult result = test::run_yaml_text(dir,
                                               "name: vmas_test\ninput: capsule.off\nstages:\n"
                                               "  - plugin: vmas\n    params:\n      target_spheres: 6\n      edits: |\n"
                                               "        - split [0, 0, 0.6] after end\n"
                                               "  - plugin: vmas_dual\noutputs:\n  medial: [ma]\n",
                                               registry);
  INFO(result.error);
  REQUIRE(result.ok);
  const MedialComplex mc = read_ma(dir / "run" / "medial.ma");
  CHECK(mc.num_vertices() == 7);
  CHECK(mc.edges.size() == 6);
  CHECK(mc.faces.empty());

  // The shipped pipelines validate when the plugins they name are built.
  Registry all;
  all.load_default();
  if (all.find("normalize") && all.find("reconstruction") && all.find("vmas") && all.find("sample")) {
    CHECK_NOTHROW(load_pipeline(test::source_dir() / "pipelines" / "vmas.yaml", all));
    CHECK_NOTHROW(load_pipeline(test::source_dir() / "pipelines" / "vmas_samples.yaml", all));
  } else {
    WARN("pipelines/vmas.yaml and vmas_samples.yaml not validated: normalize, sample or reconstruction is not "
         "built yet");
  }
}

