#pragma once
// The msd package's stages (docs/plugins/msd.md): `msd` turns the scene's medial mesh M into the
// Medial Skeletal Diagram (a simplification: the skeleton replaces M), `msd_medial` reads M from
// the authors' JSON format when the pipeline has no extraction stage.
#include "optimisation.hpp"
#include "output.hpp"
#include "reconstruction.hpp"
#include "refinement.hpp"
#include "union_surface.hpp"

#include <medax/stage.hpp>

#include <chrono>
#include <string>

namespace medax::msd {

/// How Ŝ is built and published: the boundary of the union without a grid, a signed-distance
/// grid, or not at all.
enum class ReconstructionMode { Union, Sdf, None };

class MsdStage : public SimplificationStage {
 public:
  using Clock = std::chrono::steady_clock;
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  void declare_optimisation(ParamBinder& p);
  void declare_fitting(ParamBinder& p);
  void declare_construction(ParamBinder& p);
  void declare_outputs(ParamBinder& p);
  std::vector<RefinedPrimitive> final_primitives(const TargetMesh& target, const Diagram& best,
                                                 RefinementSummary& summary, Context& ctx) const;
  void write_outputs(const Shape& shape, const OptimisationResult& result,
                     const std::vector<RefinedPrimitive>& primitives, Summary& summary, Clock::time_point start,
                     Context& ctx);
  void publish_reconstruction(const Shape& shape, const std::vector<RefinedPrimitive>& primitives, Summary& summary,
                              Context& ctx) const;

  OptimisationOptions options_;
  bool refine_ = true;
  RefineOptions refine_options_;
  ReconstructionMode reconstruction_ = ReconstructionMode::None;
  SdfOptions sdf_;
  UnionOptions union_;
  bool write_primitives_ = true;
};

class MsdMedialStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;

 private:
  std::string medial_file_;
};

}  // namespace medax::msd
