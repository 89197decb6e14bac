#include "top_sim/model.hpp"

namespace top_sim {

const char* to_string(NormalForceModel m) {
  return m == NormalForceModel::constrained ? "constrained" : "static";
}

double static_friction(const Model& model) {
  if (model.normal_force == NormalForceModel::static_approximation || model.kind == ModelKind::adiabatic) return 0.0;
  return model.contact.static_friction ? *model.contact.static_friction : friction_coefficient(model.friction, 0.0);
}

const char* to_string(ModelKind k) { return k == ModelKind::full ? "full" : "adiabatic"; }

const char* kind_name(const Model& model) { return model.automatic.enabled ? "auto" : to_string(model.kind); }

}  // namespace top_sim
