#pragma once
// The six stage interfaces. A stage is a thin, declarative face (StageInfo with its parameters)
// over an algorithm that lives in its own files.
#include <medax/context.hpp>
#include <medax/medial_complex.hpp>
#include <medax/metrics.hpp>
#include <medax/params.hpp>
#include <medax/role.hpp>
#include <medax/scene_data.hpp>
#include <medax/surface.hpp>

#include <optional>
#include <string_view>
#include <string>
#include <vector>

namespace medax {

/// Everything a pipeline carries from stage to stage.
struct Scene {
  Shape shape;
  std::optional<MedialComplex> medial;
  std::map<std::string, Metrics> metrics;  ///< per evaluation stage id
  SceneData data;                          ///< typed payloads stages pass on (scene_data.hpp)
};

/// Self-description of a stage: shown by `medax plugins` / `medax describe`, used to validate.
struct StageInfo {
  std::string name;     ///< unique across all plugins, e.g. "voronoi"
  std::string summary;  ///< one line
  std::string doc;      ///< docs page, e.g. "docs/plugins/voronoi.md"
  std::vector<ParamSpec> params;  ///< filled in by the registrar from the stage's declare()
  Role role = Role::Extraction;  ///< filled in by the registrar from the interface
};

/// A part of the shape that some stages need and others make (a mesh is what an input file
/// gives; samples come from a stage such as `sample`).
enum class ShapePart { Samples };
std::string_view to_string(ShapePart part);

class Stage {
 public:
  virtual ~Stage();

  /// Binds each parameter to the field that holds it (params.hpp). Default: no parameters.
  virtual void declare(ParamBinder& params);
  /// Writes validated values into the bound fields; parameters not in `values` keep their value
  /// (so a stage built in a test runs at its defaults without configure()).
  void configure(const ParamSet& values);
  /// The declared parameters, with the current field values as defaults (the declared defaults
  /// on a fresh stage).
  std::vector<ParamSpec> param_specs();

  /// The stage's id in the pipeline (its plugin name unless the YAML gives `id`).
  void set_id(std::string id) { id_ = std::move(id); }
  const std::string& id() const { return id_; }

  /// Checks what the declarations cannot (a script's syntax, two parameters that exclude each
  /// other): called when the pipeline is validated, before anything runs. Throw
  /// std::invalid_argument saying what to do. Default: nothing to check.
  virtual void check_params() const;
  /// The parts of the shape this stage needs with its parameters, and those it makes for later
  /// stages, known without data: validation checks that the input or an earlier stage makes
  /// each need, so `medax validate` refuses what `run` would refuse at once. Default: none.
  virtual std::vector<ShapePart> needs() const;
  virtual std::vector<ShapePart> makes() const;
  /// Checks the scene before any work: first the role's own needs (a medial complex for all but
  /// conditioning and extraction), then the stage's check_scene(). Throws std::invalid_argument.
  void prepare(const Scene& scene) const;
  /// Runs the stage on the scene; the role interfaces below implement it.
  virtual void run(Scene& scene, Context& ctx) = 0;

 protected:
  /// The stage's own checks of the data against its parameters (throw std::invalid_argument with
  /// what to do). Default: nothing to check.
  virtual void check_scene(const Scene& scene) const;

 private:
  /// What the role itself needs of the scene; each role interface implements it once.
  virtual void check_role(const Scene& scene) const = 0;

  std::string id_;
};

/// Conditioning: changes the shape (normalise, repair, sample).
class ConditioningStage : public Stage {
 public:
  static constexpr Role kRole = Role::Conditioning;
  ~ConditioningStage() override;
  virtual void condition(Shape& shape, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

/// Extraction: computes a medial complex from the shape.
class ExtractionStage : public Stage {
 public:
  static constexpr Role kRole = Role::Extraction;
  ~ExtractionStage() override;
  virtual MedialComplex extract(const Shape& shape, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

/// Significance: adds a named scalar field to the complex's elements.
class SignificanceStage : public Stage {
 public:
  static constexpr Role kRole = Role::Significance;
  ~SignificanceStage() override;
  virtual void measure(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

/// Simplification: replaces the complex with a smaller one.
class SimplificationStage : public Stage {
 public:
  static constexpr Role kRole = Role::Simplification;
  ~SimplificationStage() override;
  virtual void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

/// Connectivity: builds edges/triangles, labels, sheets or paths on the complex's spheres.
class ConnectivityStage : public Stage {
 public:
  static constexpr Role kRole = Role::Connectivity;
  ~ConnectivityStage() override;
  virtual void connect(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

/// Evaluation: measures the complex against the shape.
class EvaluationStage : public Stage {
 public:
  static constexpr Role kRole = Role::Evaluation;
  ~EvaluationStage() override;
  virtual Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) = 0;
  /// Stores the metrics under the stage's id.
  void run(Scene& scene, Context& ctx) final;

 private:
  void check_role(const Scene& scene) const final;
};

}  // namespace medax
