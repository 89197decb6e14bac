#include "param_yaml.hpp"

#include <stdexcept>

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

YAML::Node scene_yaml(XmlRpc::XmlRpcValue& tree, const std::set<std::string>& drop, const std::string& where) {
  YAML::Node map(YAML::NodeType::Map);
  if (tree.getType() != XmlRpc::XmlRpcValue::TypeStruct) return map;  // no parameters: the core's defaults
  for (auto& kv : tree)
    if (!drop.count(kv.first)) map[kv.first] = to_yaml(kv.second, where + "/" + kv.first);
  return map;
}

}  // namespace top_sim_ros
