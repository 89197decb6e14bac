#include "param_yaml.hpp"

#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "top_sim/friction.hpp"
#include "top_sim/state.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim_ros {

YAML::Node to_yaml(XmlRpc::XmlRpcValue& v, const std::string& where) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(static_cast<bool>(v));
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeDouble: return YAML::Node(static_cast<double>(v));
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(static_cast<std::string>(v));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node seq(YAML::NodeType::Sequence);
      for (int i = 0; i < v.size(); ++i) seq.push_back(to_yaml(v[i], where + "[" + std::to_string(i) + "]"));
      return seq;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto& kv : v) map[kv.first] = to_yaml(kv.second, where + "/" + kv.first);
      return map;
    }
    default:
      throw std::runtime_error(where + ": unsupported parameter type (must be a bool, number, string, list or map)");
  }
}

const std::set<std::string>& reconfigure_physics_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = {"alpha",        "spin",      "friction_law", "patch_radius",
                               "rolling_resistance", "spin_drag", "drag"};
    for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) k.insert(p.name);
    return k;
  }();
  return keys;
}

namespace {
double number(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw std::runtime_error(where + " = " + v.toXml() + ": must be a number");
}

// The finite-contact and air values found at start, each only where it differs from the scene's: a value left on
// the parameter server by an earlier run that equals the scene's does not replace a scene's hertz patch.
void finite_start(XmlRpc::XmlRpcValue& tree, const top_sim::Model& model, const std::string& where,
                  top_sim::Command& c) {
  const std::tuple<const char*, std::optional<double> top_sim::Command::*, double> fields[] = {
      {"patch_radius", &top_sim::Command::patch_radius, model.finite_contact.patch_radius},
      {"rolling_resistance", &top_sim::Command::rolling_resistance, model.finite_contact.rolling_resistance},
      {"spin_drag", &top_sim::Command::spin_drag, model.air.spin_drag},
      {"drag", &top_sim::Command::drag, model.air.drag}};
  for (const auto& [name, member, in_scene] : fields) {
    if (!tree.hasMember(name)) continue;
    const double v = number(tree[name], where + "/" + name);
    if (v != in_scene) c.*member = v;
  }
}
}  // namespace

top_sim::Command start_command(XmlRpc::XmlRpcValue& tree, const top_sim::Model& model, const std::string& where) {
  top_sim::Command c;
  if (tree.getType() != XmlRpc::XmlRpcValue::TypeStruct) return c;
  if (tree.hasMember("alpha")) c.inclination = number(tree["alpha"], where + "/alpha");
  if (tree.hasMember("spin")) c.spin = number(tree["spin"], where + "/spin");
  top_sim::FrictionChange change;  // over the scene's law, applied by the core
  bool friction = false;
  if (tree.hasMember("friction_law")) {
    XmlRpc::XmlRpcValue& v = tree["friction_law"];
    top_sim::FrictionLawKind kind;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString ||
        !top_sim::parse_friction_law_kind(static_cast<std::string>(v), kind))
      throw std::runtime_error(where + "/friction_law = " + v.toXml() + ": must be one of " +
                               top_sim::friction_law_names(", "));
    change.kind = kind;
    friction = true;
  }
  const top_sim::FrictionLawKind kind = change.kind ? *change.kind : model.friction.kind;
  for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) {
    if (!tree.hasMember(p.name)) continue;
    const double v = number(tree[p.name], where + "/" + p.name);  // every law's key is checked
    if (p.law != kind) continue;  // dynamic_reconfigure stores every law's fields: only this law's are the change
    change.given.emplace_back(&p, v);
    friction = true;
  }
  if (friction) c.friction = std::move(change);
  finite_start(tree, model, where, c);
  return c;
}

top_sim::Scene start_scene(top_sim::Scene scene, const top_sim::Command& start) {
  top_sim::apply_to_model(start, scene.model);
  if (start.spin) scene.initial.spin = *start.spin;
  if (scene.initial.start == top_sim::StartKind::stationary) {
    const top_sim::StationaryState st = top_sim::stationary_state(scene.model, scene.initial.spin);
    if (!st.exists) throw std::runtime_error("initial.start 'stationary' is impossible at the start values: " + st.reason);
  }
  return scene;
}

}  // namespace top_sim_ros
