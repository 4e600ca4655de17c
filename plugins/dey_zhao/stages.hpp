#pragma once
// The stage of the dey_zhao package: MEDIAL (Dey & Zhao 2004) as an extraction stage, a thin
// face over medial.hpp that declares the parameters, checks them against the data, and calls it.
#include "medial.hpp"

#include <medax/stage.hpp>

namespace medax::dey_zhao {

/// Where the Delaunay points come from.
enum class PointSource { Auto, Vertices, Samples };

/// `dey_zhao`: the Voronoi facets selected by the Angle and Ratio conditions.
class DeyZhaoStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;
  std::vector<ShapePart> needs() const override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  bool use_samples(const Shape& shape) const;
  /// Refuses, with what to do, data this stage cannot work on.
  void check(const Shape& shape) const;

  PointSource points_ = PointSource::Auto;
  MedialOptions options_;  // every field but generator_kind and parallel is a parameter
};

}  // namespace medax::dey_zhao
