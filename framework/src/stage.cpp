#include <medax/stage.hpp>

#include <stdexcept>

namespace medax {

// Out-of-line destructors anchor each interface's type information in the kernel library, so
// dynamic_cast works across plugin boundaries.
Stage::~Stage() = default;
ConditioningStage::~ConditioningStage() = default;
ExtractionStage::~ExtractionStage() = default;
SignificanceStage::~SignificanceStage() = default;
SimplificationStage::~SimplificationStage() = default;
ConnectivityStage::~ConnectivityStage() = default;
EvaluationStage::~EvaluationStage() = default;

void Stage::declare(ParamBinder&) {}
void Stage::check_params() const {}
std::vector<ShapePart> Stage::needs() const { return {}; }
std::vector<ShapePart> Stage::makes() const { return {}; }

std::string_view to_string(ShapePart part) {
  switch (part) {
    case ShapePart::Samples: return "samples";
  }
  return "?";
}
void Stage::check_scene(const Scene&) const {}

void Stage::configure(const ParamSet& values) {
  ParamBinder binder;
  declare(binder);
  binder.apply(values);
}

std::vector<ParamSpec> Stage::param_specs() {
  ParamBinder binder;
  declare(binder);
  return {binder.specs().begin(), binder.specs().end()};
}

void Stage::prepare(const Scene& scene) const {
  check_role(scene);
  check_scene(scene);
}

namespace {
void require_medial(const Scene& scene, Role role) {
  if (!scene.medial)
    throw std::invalid_argument(std::string("a ") + std::string(to_string(role)) +
                                " stage needs a medial complex: put an extraction stage before it"
                                " or give `medial_input:`");
}
}  // namespace

void ConditioningStage::check_role(const Scene&) const {}
void ConditioningStage::run(Scene& scene, Context& ctx) { condition(scene.shape, ctx); }

void ExtractionStage::check_role(const Scene&) const {}
void ExtractionStage::run(Scene& scene, Context& ctx) { scene.medial = extract(scene.shape, ctx); }

void SignificanceStage::check_role(const Scene& scene) const { require_medial(scene, kRole); }
void SignificanceStage::run(Scene& scene, Context& ctx) { measure(scene.shape, *scene.medial, ctx); }

void SimplificationStage::check_role(const Scene& scene) const { require_medial(scene, kRole); }
void SimplificationStage::run(Scene& scene, Context& ctx) { simplify(scene.shape, *scene.medial, ctx); }

void ConnectivityStage::check_role(const Scene& scene) const { require_medial(scene, kRole); }
void ConnectivityStage::run(Scene& scene, Context& ctx) { connect(scene.shape, *scene.medial, ctx); }

void EvaluationStage::check_role(const Scene& scene) const { require_medial(scene, kRole); }
void EvaluationStage::run(Scene& scene, Context& ctx) { scene.metrics[id()] = evaluate(scene.shape, *scene.medial, ctx); }

}  // namespace medax
