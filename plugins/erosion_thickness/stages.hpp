#pragma once
// The erosion_thickness package's stages (docs/plugins/erosion_thickness.md): thin faces over
// erosion_thickness.hpp, local_measures.hpp and pure_complex.hpp. Declared here so tests can
// call them directly.
#include <medax/stage.hpp>

namespace medax::et {

/// Burn time and Erosion Thickness per vertex (Yan et al. 2016, §6).
class ErosionThicknessStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// The medial radius R as a significance field (the paper's simplest local measure).
class RadiusMeasureStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Object angle: the largest angle at the centre between two generators.
class ObjectAngleStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Circumradius of the generators (lambda of the lambda-medial axis).
class CircumradiusStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Medial curves dual to the burn trees, with ET_C (§7.1-7.2). Replaces the complex.
class MedialCurvesStage : public ConnectivityStage {
 public:
  static StageInfo describe();
  void connect(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// ET skeleton: topology-preserving contraction protecting significant sheets and curves (§7.3).
class EtSkeletonStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

/// Clean-up to a pure 2-complex: weld, drop degenerate/duplicate faces, dangling edges and
/// isolated vertices. A simplification stage because it works on the medial complex
/// (conditioning stages work on the shape).
class PureComplexStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

}  // namespace medax::et
