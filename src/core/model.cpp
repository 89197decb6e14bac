#include "top_sim/model.hpp"

namespace top_sim {

const char* to_string(NormalForceModel m) {
  return m == NormalForceModel::constrained ? "constrained" : "static";
}

const char* to_string(ModelKind k) { return k == ModelKind::full ? "full" : "adiabatic"; }

}  // namespace top_sim
