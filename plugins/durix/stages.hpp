#pragma once
// The durix package's stages: `delaunay_surface` (conditioning), `durix` (extraction) and
// `durix_epsilon` (the ε-oracle, a significance stage injected into `durix`). Thin faces over
// remesh_fallback.hpp and durix.hpp.
#include "durix.hpp"
#include "remesh_fallback.hpp"
#include "significance.hpp"

#include <medax/stage.hpp>

#include <memory>

namespace medax::durix {

/// The interface `durix` expects from its `oracle` parameter: any significance stage of this
/// package that can make a RegionOracle for a shape.
class DurixOracle : public SignificanceStage {
 public:
  virtual std::unique_ptr<RegionOracle> make_oracle(const Shape& shape) const = 0;
};

class EpsilonOracleStage : public DurixOracle {
 public:
  static StageInfo describe();
  std::unique_ptr<RegionOracle> make_oracle(const Shape& shape) const override;
  /// Per medial vertex: `durix_coverage` (surface vertices within r + ε of the ball) and
  /// `durix_unique_coverage` (of which covered by no other inflated ball).
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
  double absolute_epsilon(const Shape& shape) const;
};

class DelaunaySurfaceStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  void condition(Shape& shape, Context& ctx) override;

 private:
  DelaunaySurfaceOptions conversion_options() const;
  /// Logs the flips and splits; false when the mesh was already Delaunay (nothing to replace).
  static bool log_dzm07(const DelaunayMeshReport& report, Context& ctx);
};

class DurixStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;
  /// The full result of the last extract() (M_w, segmentation, report), for tests and tools.
  const DurixResult& last_result() const { return last_; }

 private:
  void check(const Shape& shape) const;
  DurixResult last_;
};

/// `durix` parameters at their defaults, with a `durix_epsilon` oracle at `epsilon` (relative to
/// the bounding-box diagonal): for direct calls from tests and tools.
ParamSet durix_params(double epsilon = 0.01);

}  // namespace medax::durix
