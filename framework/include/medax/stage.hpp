#pragma once
// The six stage interfaces. A stage is a thin, declarative face (StageInfo with its parameters)
// over an algorithm that lives in its own files.
#include <medax/context.hpp>
#include <medax/medial_complex.hpp>
#include <medax/metrics.hpp>
#include <medax/params.hpp>
#include <medax/role.hpp>
#include <medax/surface.hpp>

#include <optional>
#include <string>
#include <vector>

namespace medax {

/// Everything a pipeline carries from stage to stage.
struct Scene {
  Shape shape;
  std::optional<MedialComplex> medial;
  std::map<std::string, Metrics> metrics;  ///< per evaluation stage id
};

/// Self-description of a stage: shown by `medax plugins` / `medax describe`, used to validate.
struct StageInfo {
  std::string name;     ///< unique across all plugins, e.g. "voronoi"
  std::string summary;  ///< one line
  std::string doc;      ///< docs page, e.g. "docs/plugins/voronoi.md"
  std::vector<ParamSpec> params;
  Role role = Role::Extraction;  ///< filled in by the registrar from the interface
};

class Stage {
 public:
  virtual ~Stage();

  /// Called once with the validated parameters before any run.
  void configure(ParamSet params) { params_ = std::move(params); }
  const ParamSet& params() const { return params_; }
  /// The stage's id in the pipeline (its plugin name unless the YAML gives `id`).
  void set_id(std::string id) { id_ = std::move(id); }
  const std::string& id() const { return id_; }

  /// Checks what the declarations cannot (a script's syntax, two parameters that exclude each
  /// other): called when the pipeline is validated, before anything runs. Throw
  /// std::invalid_argument saying what to do. Default: nothing to check.
  virtual void check_params() const;
  /// Checks the parameters against the data before any work (throw std::invalid_argument with
  /// what to do). Default: nothing to check.
  virtual void prepare(const Scene& scene) const;
  /// Runs the stage on the scene; the role interfaces below implement it.
  virtual void run(Scene& scene, Context& ctx) = 0;

 private:
  ParamSet params_;
  std::string id_;
};

/// Conditioning: changes the shape (normalise, repair, sample).
class ConditioningStage : public Stage {
 public:
  static constexpr Role kRole = Role::Conditioning;
  ~ConditioningStage() override;
  virtual void condition(Shape& shape, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;
};

/// Extraction: computes a medial complex from the shape.
class ExtractionStage : public Stage {
 public:
  static constexpr Role kRole = Role::Extraction;
  ~ExtractionStage() override;
  virtual MedialComplex extract(const Shape& shape, Context& ctx) = 0;
  void run(Scene& scene, Context& ctx) final;
};

/// Significance: adds a named scalar field to the complex's elements.
class SignificanceStage : public Stage {
 public:
  static constexpr Role kRole = Role::Significance;
  ~SignificanceStage() override;
  virtual void measure(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void prepare(const Scene& scene) const override;
  void run(Scene& scene, Context& ctx) final;
};

/// Simplification: replaces the complex with a smaller one.
class SimplificationStage : public Stage {
 public:
  static constexpr Role kRole = Role::Simplification;
  ~SimplificationStage() override;
  virtual void simplify(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void prepare(const Scene& scene) const override;
  void run(Scene& scene, Context& ctx) final;
};

/// Connectivity: builds edges/triangles, labels, sheets or paths on the complex's spheres.
class ConnectivityStage : public Stage {
 public:
  static constexpr Role kRole = Role::Connectivity;
  ~ConnectivityStage() override;
  virtual void connect(const Shape& shape, MedialComplex& medial, Context& ctx) = 0;
  void prepare(const Scene& scene) const override;
  void run(Scene& scene, Context& ctx) final;
};

/// Evaluation: measures the complex against the shape.
class EvaluationStage : public Stage {
 public:
  static constexpr Role kRole = Role::Evaluation;
  ~EvaluationStage() override;
  virtual Metrics evaluate(const Shape& shape, const MedialComplex& medial, Context& ctx) = 0;
  void prepare(const Scene& scene) const override;
  /// Stores the metrics under the stage's id.
  void run(Scene& scene, Context& ctx) final;
};

}  // namespace medax
