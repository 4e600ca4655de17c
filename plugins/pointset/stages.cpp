// The five stages: outliers, normals, smooth_points, simplify_points (the cloud in the shape's
// samples) and reconstruct_mesh (a mesh of it for the stages that need one).
#include "stages.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace medax::pointset {

namespace {

constexpr const char* kDoc = "docs/plugins/pointset.md";

/// The cloud every stage works on: refuses a shape without samples.
const OrientedSamples& cloud_of(const Shape& shape) {
  if (shape.samples.empty())
    throw std::invalid_argument("the shape has no points: point-set stages work on a point cloud (an .xyz or .pts "
                                "file, or a PLY, OFF or OBJ file without faces) or on the samples of a `sample` "
                                "stage");
  return shape.samples;
}

void declare_k(ParamBinder& p, std::size_t& k, const char* doc) { p.add("k", k, doc).at_least(2).in_unit("points"); }

}  // namespace

// ---- outliers --------------------------------------------------------------------------------

StageInfo OutliersStage::describe() {
  return {"outliers", "Removes the points far from their neighbours (CGAL remove_outliers)",
          std::string(kDoc) + "#outliers"};
}

void OutliersStage::declare(ParamBinder& p) {
  declare_k(p, options_.k, "neighbours of the root mean squared distance that scores each point");
  p.add("distance", options_.distance,
        "a point is an outlier when its score exceeds this many average spacings (CGAL's example uses 2)")
      .at_least(0)
      .in_unit("average spacing");
  p.add("max_percent", options_.max_percent, "remove at most this share of the points (the worst scores first)")
      .range(0, 100)
      .in_unit("%");
}

void OutliersStage::check_scene(const Scene& scene) const { check_cloud(cloud_of(scene.shape), options_.k, "outlier removal"); }

void OutliersStage::condition(Shape& shape, Context& ctx) {
  const std::size_t before = shape.samples.size();
  const std::size_t removed = remove_outliers(shape.samples, options_);
  ctx.info(fmt::format("removed {} of {} points as outliers", removed, before));
}

// ---- normals ---------------------------------------------------------------------------------

StageInfo NormalsStage::describe() {
  return {"normals", "Estimates point normals (jet or PCA) and orients them outward (minimum spanning tree)",
          std::string(kDoc) + "#normals"};
}

void NormalsStage::declare(ParamBinder& p) {
  p.add("estimate", estimate_, {{"auto", Estimate::Auto}, {"always", Estimate::Always}, {"never", Estimate::Never}},
        "estimate the normals: when the cloud has none (auto), always (replacing the file's), or never (orient the "
        "file's only)");
  p.add("method", options_.method, {{"jet", NormalMethod::Jet}, {"pca", NormalMethod::Pca}},
        "jet: a quadric fitted to the neighbours (CGAL jet_estimate_normals); pca: their plane");
  declare_k(p, options_.k, "neighbours of the estimate and of the orientation's graph");
  p.add("orient", options_.orient,
        "orient the normals consistently with a minimum spanning tree from the highest point, made to face +z "
        "(CGAL mst_orient_normals); points it cannot reach are removed");
}

bool NormalsStage::estimates(const OrientedSamples& cloud) const {
  return estimate_ == Estimate::Always || (estimate_ == Estimate::Auto && cloud.normals.size() != cloud.size());
}

void NormalsStage::check_scene(const Scene& scene) const {
  const OrientedSamples& cloud = cloud_of(scene.shape);
  if (estimate_ == Estimate::Never && cloud.normals.size() != cloud.size())
    throw std::invalid_argument("`estimate: never` but the points have no normals: use `estimate: auto`");
  check_cloud(cloud, options_.k, estimates(cloud) ? "normal estimation" : "normal orientation");
}

void NormalsStage::condition(Shape& shape, Context& ctx) {
  const bool estimate = estimates(shape.samples);
  const NormalReport report = estimate_and_orient_normals(shape.samples, estimate, options_);
  if (estimate)
    ctx.info(fmt::format("estimated {} normals ({}, k = {}){}", shape.samples.size(),
                         options_.method == NormalMethod::Jet ? "jet" : "pca", options_.k,
                         options_.orient ? " and oriented them" : ", not oriented"));
  else
    ctx.info(fmt::format("oriented the file's normals: {} of {} reversed", report.flipped, shape.samples.size()));
  if (report.dropped)
    ctx.warn(fmt::format("removed {} points the orientation could not reach from the others (isolated groups); "
                         "raise `k` to keep them",
                         report.dropped));
}

// ---- smooth_points ---------------------------------------------------------------------------

StageInfo SmoothPointsStage::describe() {
  return {"smooth_points", "Moves each point onto a jet fitted to its neighbours (CGAL jet_smooth_point_set)",
          std::string(kDoc) + "#smooth_points"};
}

void SmoothPointsStage::declare(ParamBinder& p) { declare_k(p, k_, "neighbours of the fitted jet"); }

void SmoothPointsStage::check_scene(const Scene& scene) const { check_cloud(cloud_of(scene.shape), k_, "jet smoothing"); }

void SmoothPointsStage::condition(Shape& shape, Context& ctx) {
  jet_smooth(shape.samples, k_);
  ctx.info(fmt::format("smoothed {} points (k = {})", shape.samples.size(), k_));
}

// ---- simplify_points -------------------------------------------------------------------------

StageInfo SimplifyPointsStage::describe() {
  return {"simplify_points", "Fewer, evener points: grid clustering or WLOP (CGAL)",
          std::string(kDoc) + "#simplify_points"};
}

void SimplifyPointsStage::declare(ParamBinder& p) {
  p.add("method", options_.method, {{"grid", SimplifyMethod::Grid}, {"wlop", SimplifyMethod::Wlop}},
        "grid: one point per cell (keeps normals); wlop: weighted locally optimal projection (new points, normals "
        "dropped: estimate them after)");
  p.add("cell", options_.cell, "grid: cell side").at_least(0).in_unit("bbox diagonal");
  p.add("select_percent", options_.select_percent, "wlop: share of the points kept").range(0, 100).in_unit("%");
  p.add("neighbor_radius", options_.neighbor_radius, "wlop: neighbourhood radius").at_least(0).in_unit("bbox diagonal");
}

void SimplifyPointsStage::check_scene(const Scene& scene) const { check_cloud(cloud_of(scene.shape), 3, "simplification"); }

void SimplifyPointsStage::condition(Shape& shape, Context& ctx) {
  const std::size_t before = shape.samples.size();
  const bool had_normals = shape.samples.normals.size() == before;
  const std::size_t removed = simplify(shape.samples, options_);
  ctx.info(fmt::format("{} of {} points kept", before - removed, before));
  if (had_normals && shape.samples.normals.empty())
    ctx.warn("WLOP made new points without normals: put a `normals` stage after this one");
}

// ---- reconstruct_mesh ------------------------------------------------------------------------

StageInfo ReconstructMeshStage::describe() {
  return {"reconstruct_mesh",
          "A triangle mesh of the point cloud (CGAL Poisson or advancing front) for the stages that need a mesh",
          std::string(kDoc) + "#reconstruct_mesh"};
}

void ReconstructMeshStage::declare(ParamBinder& p) {
  p.add("method", options_.method,
        {{"poisson", ReconstructionMethod::Poisson}, {"advancing_front", ReconstructionMethod::AdvancingFront}},
        "poisson: a closed surface near the points (needs oriented normals); advancing_front: triangles between "
        "the points themselves (may leave holes)");
  p.add("distance", options_.distance, "poisson: approximation distance of the surface mesher (CGAL sm_distance)")
      .at_least(0)
      .in_unit("average spacing");
  p.add("angle", options_.angle, "poisson: smallest triangle angle of the surface mesher (CGAL sm_angle)")
      .range(0, 30)
      .in_unit("deg");
  p.add("radius_ratio_bound", options_.radius_ratio_bound,
        "advancing_front: candidate triangles with a larger radius ratio are not added")
      .at_least(0);
}

void ReconstructMeshStage::check_scene(const Scene& scene) const {
  const OrientedSamples& cloud = cloud_of(scene.shape);
  check_cloud(cloud, 6, "surface reconstruction");
  if (options_.method == ReconstructionMethod::Poisson && cloud.normals.size() != cloud.size())
    throw std::invalid_argument("`method: poisson` needs oriented normals and the points have none: put a `normals` "
                                "stage before this one, or use `method: advancing_front`");
}

void ReconstructMeshStage::condition(Shape& shape, Context& ctx) {
  ReconstructionReport report;
  shape.mesh = reconstruct_surface(shape.samples, options_, &report);
  ctx.info(fmt::format("reconstructed {} vertices, {} triangles; {} border edges", shape.mesh.vertices.size(),
                       shape.mesh.faces.size(), report.border_edges));
  if (report.border_edges)
    ctx.warn(fmt::format("the mesh is open ({} border edges): put `repair` with `fill_holes: true` after this "
                         "stage for the methods that need a closed surface",
                         report.border_edges));
}

}  // namespace medax::pointset
