#pragma once
// The evaluation package's stages: thin faces over reconstruction.hpp, counts.hpp and the
// topology service. Declared here so tests can call them directly.
#include <medax/stage.hpp>

namespace medax::evaluation {

/// Distances between the input surface and the sphere/cone/slab envelope of the complex.
class Reconstruction : public EvaluationStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;
};

/// #v, #e, #f, N_d and N_c as MSD counts them.
class Counts : public EvaluationStage {
 public:
  static StageInfo describe();
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;
};

/// Components, Euler characteristic and Betti numbers of the complex, beside the input's.
class Topology : public EvaluationStage {
 public:
  static StageInfo describe();
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;
};

}  // namespace medax::evaluation
