#pragma once
// The evaluation package's stages: thin faces over reconstruction.hpp, counts.hpp and the
// topology service. Declared here so tests can call them directly.
#include "reconstruction.hpp"

#include <medax/reconstructed_surface.hpp>
#include <medax/stage.hpp>

namespace medax::evaluation {

/// Distances between the input surface and the sphere/cone/slab envelope of the complex, or the
/// rebuilt surface (kReconstructedSurface) when an earlier stage published one.
class ReconstructionStage : public EvaluationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  Metrics measure_rebuilt(const Shape& shape, const ReconstructedSurface& rebuilt, Context& ctx);
  Metrics measure_envelope(const Shape& shape, const MedialComplex& medial, Context& ctx);

  ReconstructionOptions options_;
  bool export_envelope_ = false;
};

/// #v, #e, #f, N_d and N_c as MSD counts them; N_d and N_c from kRepresentationSize when an
/// earlier stage published it.
class CountsStage : public EvaluationStage {
 public:
  static StageInfo describe();
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;
};

/// Components, Euler characteristic and Betti numbers of the complex, beside the input's.
class TopologyStage : public EvaluationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) override;

 private:
  bool input_ = true;
};

}  // namespace medax::evaluation
