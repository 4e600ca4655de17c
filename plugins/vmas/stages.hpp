#pragma once
// The vmas package's stages: thin faces over the solver (vmas.hpp) and the dual (dual.hpp).
// Declared here so tests can call them directly.
#include "dual.hpp"
#include "vmas.hpp"

#include <medax/stage.hpp>

namespace medax::vmas {

/// Extraction: variational medial axis sampling (spheres + their clusters as generators).
class VmasStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void check_params() const override;
  void prepare(const Scene& scene) const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;

  /// The solver options and input options the parameters give.
  static VmasOptions solver_options(const ParamSet& params);
  static InputOptions input_options(const ParamSet& params);
  /// Builds the VMAS input from the shape as `input` (auto|mesh|samples) says.
  static std::shared_ptr<const VmasInput> make_input(const Shape& shape, const std::string& input,
                                                     const InputOptions& options);
};

/// Connectivity: the dual of the partition (an edge per adjacent pair of clusters, a triangle
/// per 3-clique).
class VmasDualStage : public ConnectivityStage {
 public:
  static StageInfo describe();
  void prepare(const Scene& scene) const override;
  void connect(const Shape& shape, MedialComplex& medial, Context& ctx) override;
};

}  // namespace medax::vmas
