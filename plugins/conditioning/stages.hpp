#pragma once
// The conditioning package's stages: thin, declarative faces over normalization.hpp,
// repair_policy.hpp (with the mesh check/repair service) and surface_sampling.hpp. Each parameter
// is declared once, bound to the field of the options it sets (its initial value is the default).
#include "normalization.hpp"
#include "surface_sampling.hpp"

#include <medax/services/mesh_check.hpp>
#include <medax/stage.hpp>

namespace medax::conditioning {

/// Scales and centres the shape to a unit bounding box; keeps the map back to the input frame.
class NormalizeStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  NormalizeMode mode_ = NormalizeMode::Diagonal;
};

/// Checks the mesh, fixes cheap problems, and refuses (or, when asked, repairs) the rest.
class RepairStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// The options with `repair: true` applied.
  services::RepairOptions repair_options() const;

  bool repair_all_ = false;  ///< `repair`: fill holes and remove self-intersections too
  services::RepairOptions options_;
};

/// Oriented surface samples with areas: uniform, Poisson-disk, or the mesh vertices.
class SampleStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;
  std::vector<ShapePart> makes() const override { return {ShapePart::Samples}; }

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  SampleSettings settings_;
};

}  // namespace medax::conditioning
