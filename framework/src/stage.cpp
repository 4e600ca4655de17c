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

void Stage::check_params() const {}
void Stage::prepare(const Scene&) const {}

namespace {
void require_medial(const Scene& scene, Role role) {
  if (!scene.medial)
    throw std::invalid_argument(std::string("a ") + std::string(to_string(role)) +
                                " stage needs a medial complex: put an extraction stage before it"
                                " or give `medial_input:`");
}
}  // namespace

void ConditioningStage::run(Scene& scene, Context& ctx) { condition(scene.shape, ctx); }

void ExtractionStage::run(Scene& scene, Context& ctx) { scene.medial = extract(scene.shape, ctx); }

void SignificanceStage::prepare(const Scene& scene) const { require_medial(scene, kRole); }
void SignificanceStage::run(Scene& scene, Context& ctx) { measure(scene.shape, *scene.medial, ctx); }

void SimplificationStage::prepare(const Scene& scene) const { require_medial(scene, kRole); }
void SimplificationStage::run(Scene& scene, Context& ctx) {
  simplify(scene.shape, *scene.medial, ctx);
}

void ConnectivityStage::prepare(const Scene& scene) const { require_medial(scene, kRole); }
void ConnectivityStage::run(Scene& scene, Context& ctx) { connect(scene.shape, *scene.medial, ctx); }

void EvaluationStage::prepare(const Scene& scene) const { require_medial(scene, kRole); }
void EvaluationStage::run(Scene& scene, Context& ctx) {
  scene.metrics[id()] = evaluate(scene.shape, *scene.medial, ctx);
}

}  // namespace medax
