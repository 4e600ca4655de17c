#pragma once
// The conditioning package's stages: thin, declarative faces over normalization.hpp,
// repair_policy.hpp (with the mesh check/repair service) and surface_sampling.hpp.
#include <medax/stage.hpp>

namespace medax::conditioning {

/// Scales and centres the shape to a unit bounding box; keeps the map back to the input frame.
class NormalizeStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  void condition(Shape& shape, Context& ctx) override;
};

/// Checks the mesh, fixes cheap problems, and refuses (or, when asked, repairs) the rest.
class RepairStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  void condition(Shape& shape, Context& ctx) override;
};

/// Oriented surface samples with areas: uniform, Poisson-disk, or the mesh vertices.
class SampleStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  void condition(Shape& shape, Context& ctx) override;
};

}  // namespace medax::conditioning
