#pragma once
// The pointset package's conditioning stages: thin, declarative faces over point_processing.hpp
// and reconstruction.hpp. They work on the shape's samples (a point cloud read from a file, or
// samples of a mesh); each parameter is declared once, bound to the field of the options it sets.
#include "point_processing.hpp"
#include "reconstruction.hpp"

#include <medax/stage.hpp>

namespace medax::pointset {

/// Removes the points far from their neighbours (CGAL::remove_outliers).
class OutliersStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  OutlierOptions options_;
};

/// When normals are estimated rather than oriented only.
enum class Estimate { Auto, Always, Never };

/// Estimates normals (jet or PCA) and orients them (MST): the cloud becomes oriented samples.
class NormalsStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;
  std::vector<ShapePart> makes() const override { return {ShapePart::Samples}; }

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  bool estimates(const OrientedSamples& cloud) const;

  Estimate estimate_ = Estimate::Auto;
  NormalOptions options_;
};

/// Moves each point onto a jet fitted to its neighbours (CGAL::jet_smooth_point_set).
class SmoothPointsStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  std::size_t k_ = 24;
};

/// Fewer, evener points: grid clustering or WLOP.
class SimplifyPointsStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  SimplifyOptions options_;
};

/// A triangle mesh of the cloud (Poisson or advancing front) for the stages that need one; the
/// samples are kept.
class ReconstructMeshStage : public ConditioningStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void condition(Shape& shape, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  ReconstructionOptions options_;
};

}  // namespace medax::pointset
