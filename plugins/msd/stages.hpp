#pragma once
// The msd package's stages (docs/plugins/msd.md): `msd` turns the scene's medial mesh M into the
// Medial Skeletal Diagram (a simplification: the skeleton replaces M), `msd_medial` reads M from
// the authors' JSON format when the pipeline has no extraction stage.
#include "optimisation.hpp"

#include <medax/stage.hpp>

#include <string>

namespace medax::msd {

/// How Ŝ is built for the outputs.
enum class ReconstructionMode { Union, None };

class MsdStage : public SimplificationStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  void declare_optimisation(ParamBinder& p);
  void declare_fitting(ParamBinder& p);
  void declare_construction(ParamBinder& p);
  void write_outputs(const Shape& shape, const OptimisationResult& result, double seconds_total, Context& ctx);

  OptimisationOptions options_;
  ReconstructionMode reconstruction_ = ReconstructionMode::None;
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
