#include "stages.hpp"

#include <medax/services/sampling.hpp>

#include <fmt/format.h>

#include <chrono>
#include <string>
#include <stdexcept>

namespace medax::coverage_axis {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Longest side of the mesh's bounding box (1 after `normalize` with mode max_side).
double longest_side(const SurfaceMesh& mesh) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return (hi - lo).maxCoeff();
}

Balls subset(const Balls& balls, const std::vector<Index>& keep) {
  Balls out;
  for (Index i : keep) out.centres.push_back(balls.centres[i]), out.radii.push_back(balls.radii[i]);
  return out;
}

/// The coverage matrix of `balls`, timed and logged, with the uncoverable samples reported.
CoverageMatrix timed_matrix(const std::vector<Vec3>& samples, const Balls& balls, Selection& out, Context& ctx) {
  const auto t = Clock::now();
  CoverageMatrix m = coverage_matrix(samples, balls, out.dilation);
  out.seconds_matrix = seconds_since(t);
  out.uncovered = m.uncoverable;
  if (m.uncoverable > 0)
    ctx.warn(fmt::format("{} of {} samples lie in no dilated candidate ball; they are dropped from the cover "
                         "(raise `dilation` or `candidate_count` to cover them)",
                         m.uncoverable, samples.size()));
  return m;
}

/// The closing log line: the count, the certificate (exact mode) and the time per phase.
std::string summary(const Selection& s) {
  if (s.mode == "greedy")
    return fmt::format("{} spheres selected; times: candidates {:.2f} s, matrix {:.2f} s, greedy {:.2f} s",
                       s.objective, s.seconds_candidates, s.seconds_matrix, s.seconds_solve);
  const std::string certificate =
      s.proven_optimal ? fmt::format("proven optimal (LP bound {:.2f})", s.lp_bound)
                       : fmt::format("NOT proven optimal: lower bound {:.2f}, gap {:.1f}%", s.lower_bound, 100 * s.gap);
  return fmt::format("{} spheres selected, {}; warm start {} (greedy {}), {} nodes; times: candidates {:.2f} s, "
                     "matrix {:.2f} s, presolve {:.2f} s, LP {:.2f} s, local search {:.2f} s, branch and cut {:.2f} s",
                     s.objective, certificate, s.warm_start, s.greedy, s.nodes, s.seconds_candidates, s.seconds_matrix,
                     s.seconds_presolve, s.seconds_lp, s.seconds_search, s.seconds_solve);
}

}  // namespace

StageInfo CoverageAxisStage::describe() {
  return {"coverage_axis",
          "Coverage Axis (exact set cover, CBC) or Coverage Axis++ (greedy): inner spheres whose dilation covers "
          "the surface samples; marks the complex vertices qmat keeps",
          "docs/plugins/coverage_axis.md"};
}

void CoverageAxisStage::declare(ParamBinder& p) {
  p.add("mode", mode_, {{"exact", Mode::Exact}, {"greedy", Mode::Greedy}},
        "`exact`: Coverage Axis, minimum set cover by CBC after presolve; `greedy`: Coverage Axis++ selection");
  p.add("candidates", candidates_, {{"random", Candidates::Random}, {"voronoi", Candidates::Voronoi}},
        "random interior points, or the vertices of the complex in the scene with their radii");
  p.add("candidate_count", candidate_count_, "number of random interior candidates (VMAS: 20,000)").range(1, 1e8);
  p.add("radius_from", radius_from_, {{"samples", RadiusFrom::Samples}, {"mesh", RadiusFrom::Mesh}},
        "radius of a random candidate: distance to the nearest surface sample (authors' code) or to the mesh");
  p.add("samples", samples_, "number of area-uniform surface samples to cover (VMAS, CA++: 1500)").range(1, 1e8);
  p.add("dilation", dilation_,
        "δ_r added to every candidate radius, as a fraction of the mesh's longest bounding-box side (absolute "
        "in the unit box the papers use)")
      .range(0, 10);
  p.add("time_limit", exact_.time_limit, "exact mode: seconds of branch and cut before the best cover is kept")
      .range(0, 1e7)
      .in_unit("s");
  p.add("presolve", exact_.presolve,
        "exact mode: forced picks, dominated columns and rows to a fixpoint before the solve");
  p.add("target", greedy_.target, "greedy mode: K, the number of spheres to select; 0 = until every sample is "
                                  "covered")
      .range(0, 1e8);
  p.add("lambda_uniformity", greedy_.lambda_uniformity, "greedy mode: λ_u, weight of the distance to the selection")
      .range(0, 1e6);
  p.add("lambda_centrality", greedy_.lambda_centrality, "greedy mode: λ_c, weight of the small-radius penalty")
      .range(0, 1e6);
  p.add("penalty", greedy_.penalty, {{"ratio", Penalty::Ratio}, {"standardized", Penalty::Standardized}},
        "greedy mode: centrality penalty 0.1·max r / r (authors' default) or the standardized 1/r ('stand')");
}

void CoverageAxisStage::check_params() const {
  if (mode_ == Mode::Exact && greedy_.target != 0)
    throw std::invalid_argument("`target` applies to `mode: greedy` only; the exact cover has the minimum size");
}

void CoverageAxisStage::check_scene(const Scene& scene) const {
  if (scene.shape.mesh.vertices.size() < 4 || scene.shape.mesh.faces.empty())
    throw std::invalid_argument("the shape has no closed surface mesh to sample and to test insideness against "
                                "(`reconstruct_mesh` makes one of a point cloud)");
  if (scene.medial->num_vertices() == 0)
    throw std::invalid_argument("the medial complex is empty; put `voronoi` before this stage");
}

Balls CoverageAxisStage::make_candidates(const Shape& shape, const MedialComplex& medial,
                                         const std::vector<Vec3>& samples, Context& ctx) const {
  if (candidates_ == Candidates::Voronoi) return complex_balls(medial);
  Balls balls;
  balls.centres = random_interior_points(shape.mesh, candidate_count_, ctx.rng());
  balls.radii = candidate_radii(balls.centres, shape.mesh, samples, radius_from_);
  return balls;
}

void CoverageAxisStage::select_exact(const std::vector<Vec3>& samples, const Balls& balls, Selection& out,
                                     Context& ctx) const {
  auto t = Clock::now();
  const std::vector<Index> kept = exact_.presolve ? geometrically_undominated(balls, out.dilation)
                                                  : std::vector<Index>{};
  const Balls columns = exact_.presolve ? subset(balls, kept) : balls;
  out.undominated = columns.centres.size();
  out.seconds_presolve = seconds_since(t);
  const CoverageMatrix m = timed_matrix(samples, columns, out, ctx);
  auto last_log = Clock::now();
  const SolveProgress progress = [&](double seconds, double incumbent, double bound) {
    ctx.progress(exact_.time_limit > 0 ? std::min(1.0, seconds / exact_.time_limit) : 1.0, "branch and cut");
    if (seconds_since(last_log) >= 10) {
      last_log = Clock::now();
      ctx.info(fmt::format("branch and cut: {:.0f} s, best cover {}, lower bound {:.2f}", seconds, incumbent, bound));
    }
    return !ctx.cancelled();
  };
  const ExactResult r = solve_exact(m.cover, exact_, progress);
  ctx.check_cancelled();
  for (Index j : r.chosen) out.centres.push_back(columns.centres[j]), out.radii.push_back(columns.radii[j]);
  out.lp_bound = r.lp_bound;
  out.lower_bound = r.lower_bound;
  out.proven_optimal = r.proven_optimal;
  out.gap = r.gap;
  out.greedy = r.greedy;
  out.warm_start = r.warm_start;
  out.nodes = r.nodes;
  out.forced = r.presolve.forced;
  out.dominated_columns = r.presolve.dominated_columns;
  out.dominated_rows = r.presolve.dominated_rows;
  out.rows = r.presolve.rows;
  out.columns = r.presolve.columns;
  out.nonzeros = r.presolve.nonzeros;
  out.seconds_presolve += r.seconds_presolve;
  out.seconds_lp = r.seconds_lp;
  out.seconds_search = r.seconds_search;
  out.seconds_solve = r.seconds_solve;
}

void CoverageAxisStage::select_greedy(const std::vector<Vec3>& samples, const Balls& balls, Selection& out,
                                      Context& ctx) const {
  const CoverageMatrix m = timed_matrix(samples, balls, out, ctx);
  const auto t = Clock::now();
  const std::vector<Index> chosen = ca_plus_plus(m.cover, balls, greedy_);
  out.seconds_solve = seconds_since(t);
  for (Index j : chosen) out.centres.push_back(balls.centres[j]), out.radii.push_back(balls.radii[j]);
  if (!covers_all(m.cover, chosen))
    ctx.info(fmt::format("stopped at target {} before every sample was covered", greedy_.target));
}

void CoverageAxisStage::measure(const Shape& shape, MedialComplex& medial, Context& ctx) {
  Selection out;
  out.mode = mode_ == Mode::Exact ? "exact" : "greedy";
  out.candidates = candidates_ == Candidates::Random ? "random" : "voronoi";
  out.dilation = dilation_ * longest_side(shape.mesh);
  auto t = Clock::now();
  const std::vector<Vec3> samples = services::sample_uniform(shape.mesh, samples_, ctx.rng()).points;
  const Balls balls = make_candidates(shape, medial, samples, ctx);
  out.samples = samples.size();
  out.sample_points = samples;
  out.candidate_count = balls.centres.size();
  out.seconds_candidates = seconds_since(t);
  ctx.info(fmt::format("{} surface samples, {} {} candidates, dilation {:.4g}", out.samples, out.candidate_count,
                       out.candidates, out.dilation));
  if (mode_ == Mode::Exact)
    select_exact(samples, balls, out, ctx);
  else
    select_greedy(samples, balls, out, ctx);
  out.objective = out.centres.size();
  out.marked = mark_nearest_vertices(medial, out.centres);
  if (out.marked < out.objective)
    ctx.warn(fmt::format("the complex has {} vertices, fewer than the {} selected spheres; all are marked",
                         medial.num_vertices(), out.objective));
  ctx.info(summary(out));
  ctx.publish(kSelection, std::move(out));
}

}  // namespace medax::coverage_axis
