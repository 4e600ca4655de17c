// normalize: unit bounding-box diagonal (or longest side), centred at the box centre.
#include "normalization.hpp"
#include "stages.hpp"

#include <sstream>

namespace medax::conditioning {

StageInfo NormalizeStage::describe() {
  return {"normalize",
          "Centres the shape at its bounding-box centre and scales it to a unit diagonal or longest side",
          "docs/plugins/conditioning.md#normalize",
          {ParamSpec::choice("mode", "diagonal", {"diagonal", "max_side"},
                             "what becomes 1: the bounding-box diagonal or its longest side")}};
}

void NormalizeStage::prepare(const Scene& scene) const {
  compute_normalization(scene.shape, parse_normalize_mode(params().text("mode")));
}

void NormalizeStage::condition(Shape& shape, Context& ctx) {
  const Normalization n = compute_normalization(shape, parse_normalize_mode(params().text("mode")));
  apply_normalization(shape, n);
  std::ostringstream log;
  log.precision(10);
  log << "scaled by 1/" << n.size << " about (" << n.centre.x() << ", " << n.centre.y() << ", " << n.centre.z()
      << "); outputs map back to the input frame";
  ctx.info(log.str());
}

}  // namespace medax::conditioning
