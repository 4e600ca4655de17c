#pragma once
// The durix package's stages: `delaunay_surface` (conditioning), `durix` (extraction) and
// `durix_epsilon` (the ε-oracle, a significance stage injected into `durix`). Thin faces over
// remesh_fallback.hpp and durix.hpp: each parameter is bound to a field of the algorithm's
// options, whose initial value is its default.
#include "durix.hpp"
#include "remesh_fallback.hpp"
#include "significance.hpp"

#include <medax/services/mesh_check.hpp>
#include <medax/stage.hpp>

#include <memory>

namespace medax::durix {

/// The interface `durix` expects from its `oracle` parameter: any significance stage of this
/// package that can make a RegionOracle for a shape.
class DurixOracle : public SignificanceStage {
 public:
  virtual std::unique_ptr<RegionOracle> make_oracle(const Shape& shape) const = 0;
};

/// How `durix_epsilon` reads its ε.
enum class EpsilonMode { Relative, Absolute };

class EpsilonOracleStage : public DurixOracle {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  std::unique_ptr<RegionOracle> make_oracle(const Shape& shape) const override;
  /// Per medial vertex: `durix_coverage` (surface vertices within r + ε of the ball) and
  /// `durix_unique_coverage` (of which covered by no other inflated ball).
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
  double absolute_epsilon(const Shape& shape) const;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  double epsilon_ = 0.01;
  EpsilonMode mode_ = EpsilonMode::Relative;
};

class DelaunaySurfaceStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// Checks the mesh (closed, manifold, outward, ...); throws with what to do.
  void check_input(const SurfaceMesh& mesh, Context& ctx) const;
  /// Logs the flips and splits; false when the mesh was already Delaunay (nothing to replace).
  static bool log_dzm07(const DelaunayMeshReport& report, Context& ctx);
  static void log_remesh(const DelaunaySurfaceResult& result, Context& ctx);

  DelaunaySurfaceOptions options_;
  services::MeshCheckOptions check_options_;
};

class DurixStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;
  /// The full result of the last extract() (M_w, segmentation, report), for tests and tools.
  const DurixResult& last_result() const { return last_; }

 protected:
  void check_scene(const Scene& scene) const override { check(scene.shape); }

 private:
  void check(const Shape& shape) const;
  static void log_report(const DurixReport& report, Context& ctx);
  /// The extra outputs: the two PLY files now, the sheet graph as scene data.
  void write_outputs(const Shape& shape, Context& ctx) const;

  StageSlot<DurixOracle> oracle_;
  DurixOptions options_;
  bool write_surface_ = true;
  bool write_segmentation_ = true;
  bool write_sheet_graph_ = true;
  DurixResult last_;
};

/// The `oracle` parameter of `durix` set to a `durix_epsilon` oracle at `epsilon` (relative to
/// the bounding-box diagonal), for direct calls from tests and tools: `stage.configure(...)`
/// leaves the other parameters at their values.
ParamSet durix_params(double epsilon = 0.01);

}  // namespace medax::durix
