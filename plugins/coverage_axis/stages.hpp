#pragma once
// The coverage_axis stage: a thin face over candidates, coverage_matrix, set_cover_exact and
// set_cover_greedy (parameters, checks, the calls, the log lines). Declared here so tests can
// call it directly.
#include "candidates.hpp"
#include "selection.hpp"
#include "set_cover_exact.hpp"
#include "set_cover_greedy.hpp"

#include <medax/stage.hpp>

namespace medax::coverage_axis {

/// Coverage Axis (exact set cover) or Coverage Axis++ (greedy).
enum class Mode { Exact, Greedy };
/// Where the candidate balls come from.
enum class Candidates { Random, Voronoi };

/// A significance stage: it selects inner spheres that cover the surface and marks, in the
/// `selected` vertex column, the vertices of the complex in the scene that qmat must keep.
class CoverageAxisStage : public SignificanceStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  void measure(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// The candidate balls (random interior points or the complex's vertices), in the scene's frame.
  Balls make_candidates(const Shape& shape, const MedialComplex& medial, const std::vector<Vec3>& samples,
                        Context& ctx) const;
  /// Fills the selection by the exact cover of the candidates.
  void select_exact(const std::vector<Vec3>& samples, const Balls& balls, Selection& out, Context& ctx) const;
  /// Fills the selection by CA++'s greedy cover of the candidates.
  void select_greedy(const std::vector<Vec3>& samples, const Balls& balls, Selection& out, Context& ctx) const;

  Mode mode_ = Mode::Exact;
  Candidates candidates_ = Candidates::Random;
  std::size_t candidate_count_ = 20000;
  RadiusFrom radius_from_ = RadiusFrom::Samples;
  std::size_t samples_ = 1500;
  double dilation_ = 0.02;
  ExactOptions exact_;
  GreedyOptions greedy_;
};

}  // namespace medax::coverage_axis
