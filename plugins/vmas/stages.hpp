#pragma once
// The vmas package's stages: thin faces over the solver (vmas.hpp), the edit scripts (edits.hpp)
// and the dual (dual.hpp). Each parameter is declared once, bound to the field of the options it
// sets (the field's initial value is the default). Declared here so tests and tools can call them.
#include "dual.hpp"
#include "vmas.hpp"

#include <medax/stage.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace medax::vmas {

/// The surface the clusters live on: the mesh's vertices, the oriented samples (a point cloud),
/// or the mesh when there is one.
enum class Surface { Auto, Mesh, Samples };
inline const std::vector<std::pair<std::string, Surface>> kSurfaces{
    {"auto", Surface::Auto}, {"mesh", Surface::Mesh}, {"samples", Surface::Samples}};

/// The frame of the points of an edit script.
enum class EditFrame { Input, Working };

/// Extraction: variational medial axis sampling (spheres + their clusters as generators).
class VmasStage : public ExtractionStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void check_params() const override;
  MedialComplex extract(const Shape& shape, Context& ctx) override;
  std::vector<ShapePart> needs() const override;

  /// The solver and input options the parameters set.
  const VmasOptions& solver_options() const { return options_; }
  const InputOptions& input_options() const { return input_options_; }
  /// Builds the VMAS input from the shape's mesh or samples, as `surface` says.
  static std::shared_ptr<const VmasInput> make_input(const Shape& shape, Surface surface,
                                                     const InputOptions& options);

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  Surface input_ = Surface::Auto;
  VmasOptions options_;
  InputOptions input_options_;
  std::string edits_;  ///< the script (edits.hpp)
  EditFrame edit_frame_ = EditFrame::Input;
  int relax_iterations_ = 10;
  bool trace_ = false;
};

/// Connectivity: the dual of the partition (an edge per adjacent pair of clusters, a triangle
/// per 3-clique).
class VmasDualStage : public ConnectivityStage {
 public:
  static StageInfo describe();
  void declare(ParamBinder& p) override;
  void connect(const Shape& shape, MedialComplex& medial, Context& ctx) override;

 protected:
  void check_scene(const Scene& scene) const override;

 private:
  /// The partition of eq. 8 against the complex's spheres, stored as its generators; returns
  /// the surface graph the clusters are adjacent in.
  std::vector<Segment> recompute_clusters(const Shape& shape, bool on_mesh, MedialComplex& medial,
                                          std::vector<int>& cluster_of) const;

  TriangleRule triangles_ = TriangleRule::Cliques;
  Surface input_ = Surface::Auto;
  double lambda_partition_ = VmasOptions{}.lambda_partition;  // as vmas
  InputOptions input_options_ = [] {
    InputOptions o;  // knn as vmas; the clusters need no shrinking balls
    o.shrinking_balls = false;
    return o;
  }();
};

}  // namespace medax::vmas
