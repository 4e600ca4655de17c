#pragma once
// The qmat package's stage: a thin face over collapse.hpp and correction.hpp (parameters,
// checks, the saved vertices, the log lines). Declared here so tests can call it directly.
#include "collapse.hpp"

#include <medax/stage.hpp>

namespace medax::qmat {

/// Saved vertices (notes §2.6): an int vertex column, nonzero = the vertex never moves. Coverage
/// Axis writes it for its selected spheres; the output keeps it on the surviving vertices.
inline const Property<int> kSelected{Element::Vertex, "selected"};

/// Which vertices are saved.
enum class Keep { Auto, None, Selected };

/// Q-MAT edge-collapse simplification of a medial complex.
class QmatStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// One flag per vertex from the `selected` column, or none, as `keep` says.
  std::vector<char> saved_flags(const MedialComplex& medial) const;
  /// The count target: target_vertices, or the saved count when it is 0 and some are saved.
  std::size_t target(std::size_t saved) const;

  QmatOptions options_;
  Keep keep_ = Keep::Auto;
  bool correct_spheres_ = false;
};

}  // namespace medax::qmat
