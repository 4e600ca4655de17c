#pragma once
// The voronoi package's stage: a thin face over interior_voronoi.hpp (parameters, checks, the
// call, the log lines). Declared here so tests can call it directly.
#include "interior_voronoi.hpp"

#include <medax/stage.hpp>

namespace medax::voronoi {

/// Where the Delaunay points come from.
enum class Points { Vertices, Samples };

/// The interior Voronoi diagram of the surface vertices (or samples).
class VoronoiStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;
  std::vector<ShapePart> needs() const override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// Refuses, with what to do, data this stage cannot work on.
  void check(const Shape& shape) const;

  Points points_ = Points::Vertices;
  InteriorVoronoiOptions options_;  // `inside` and `connectivity` are parameters
};

}  // namespace medax::voronoi
