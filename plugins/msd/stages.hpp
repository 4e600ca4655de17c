#pragma once
// The msd package's stages (docs/plugins/msd.md): `msd` turns the scene's medial mesh M into the
// Medial Skeletal Diagram (a simplification: the skeleton replaces M), `msd_medial` reads M from
// the authors' JSON format when the pipeline has no extraction stage.
#include "optimisation.hpp"
#include "output.hpp"
#include "reconstruction.hpp"

#include <medax/stage.hpp>

#include <chrono>
#include <string>

namespace medax::msd {

/// Whether Ŝ is built (signed-distance grid) and published.
enum class ReconstructionMode { Sdf, None };

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
  void write_outputs(const Shape& shape, const OptimisationResult& result, Clock::time_point start, Context& ctx);
  void publish_reconstruction(const Shape& shape, const Diagram& best, Summary& summary, Context& ctx) const;

  OptimisationOptions options_;
  ReconstructionMode reconstruction_ = ReconstructionMode::None;
  SdfOptions sdf_;
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
