#pragma once
// The erosion_thickness package's stages (docs/plugins/erosion_thickness.md): thin faces over
// erosion_thickness.hpp, local_measures.hpp and pure_complex.hpp. Declared here so tests can
// call them directly.
//
// One burn feeds three stages: `erosion_thickness` burns the complex and publishes the burn
// (kBurnData); `et_medial_curves` and `et_skeleton` read it instead of burning again, and refuse
// a complex that is not the one it burned.
#include "erosion_thickness.hpp"
#include "skeleton.hpp"

#include <medax/stage.hpp>

namespace medax::et {

/// Burn time and Erosion Thickness per vertex (Yan et al. 2016, §6); publishes the burn.
class ErosionThicknessStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 private:
  BurnOptions options_;
  bool write_forest_ = false;
};

/// The medial radius R as a significance field (the paper's simplest local measure).
class RadiusMeasureStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// The measures on the generators of each vertex: their shared `tolerance`.
class GeneratorMeasureStage : public SignificanceStage {
 public:
  void declare(ParamBinder& p) override;

 protected:
  double tolerance_ = 1e-6;
};

/// Object angle: the largest angle at the centre between two generators.
class ObjectAngleStage : public GeneratorMeasureStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Circumradius of the generators (lambda of the lambda-medial axis).
class CircumradiusStage : public GeneratorMeasureStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Medial curves dual to the burn trees, with ET_C (§7.1-7.2), from the burn of
/// `erosion_thickness`. Replaces the complex.
class MedialCurvesStage : public ConnectivityStage {
 public:
  static StageInfo describe();
  void connect(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;
};

/// ET skeleton: topology-preserving contraction protecting significant sheets and curves (§7.3),
/// from the burn of `erosion_thickness`.
class EtSkeletonStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  SkeletonOptions options_;  // theta2, theta1, phi1 (× L) and phi2 (× L²), L the burn's reference length
};

/// Clean-up to a pure 2-complex: weld, drop degenerate/duplicate faces, dangling edges and
/// isolated vertices. A simplification stage because it works on the medial complex
/// (conditioning stages work on the shape).
class PureComplexStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 private:
  double weld_tolerance_ = 1e-9;  // × the complex's longest bbox side
};

}  // namespace medax::et
