#include "node_parameters.hpp"

#include <cmath>
#include <sstream>

#include "cpu_affinity.hpp"
#include "param_yaml.hpp"
#include "top_sim/format.hpp"

namespace top_sim_ros {

namespace {

// A parameter's value as the user wrote it ('fast', 3, true, a list of 2 values), not XML-RPC's wire form.
std::string as_typed(XmlRpc::XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeString: return "'" + static_cast<std::string>(v) + "'";
    case XmlRpc::XmlRpcValue::TypeBoolean: return static_cast<bool>(v) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeDouble: return top_sim::format_number(static_cast<double>(v));
    case XmlRpc::XmlRpcValue::TypeArray: return "a list of " + std::to_string(v.size()) + " values";
    case XmlRpc::XmlRpcValue::TypeStruct: return "a map";
    default: return "a value of another type";
  }
}

std::string type_error(const std::string& where, XmlRpc::XmlRpcValue& v, const std::string& wanted) {
  return where + " = " + as_typed(v) + ": must be " + wanted;
}

void require(bool ok, const std::string& where, double value, const std::string& range) {
  if (!ok) throw ParameterError(range_error(where, value, range));
}

}  // namespace

std::string range_error(const std::string& name, double value, const std::string& range) {
  return top_sim::range_message(name, value, range);
}

ParamReader::ParamReader(XmlRpc::XmlRpcValue tree, std::string ns) : tree_(std::move(tree)), ns_(std::move(ns)) {
  if (tree_.getType() != XmlRpc::XmlRpcValue::TypeStruct) tree_ = XmlRpc::XmlRpcValue();  // nothing under ~
}

bool ParamReader::has(const std::string& key) {
  known_.insert(key);
  return tree_.getType() == XmlRpc::XmlRpcValue::TypeStruct && tree_.hasMember(key);
}

XmlRpc::XmlRpcValue& ParamReader::raw(const std::string& key) { return tree_[key]; }

double ParamReader::number(const std::string& key, double fallback) {
  if (!has(key)) return fallback;
  XmlRpc::XmlRpcValue& v = tree_[key];
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw ParameterError(type_error(where(key), v, "a number"));
}

int ParamReader::integer(const std::string& key, int fallback) {
  if (!has(key)) return fallback;
  XmlRpc::XmlRpcValue& v = tree_[key];
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw ParameterError(type_error(where(key), v, "an integer"));
}

bool ParamReader::flag(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  XmlRpc::XmlRpcValue& v = tree_[key];
  if (v.getType() == XmlRpc::XmlRpcValue::TypeBoolean) return static_cast<bool>(v);
  throw ParameterError(type_error(where(key), v, "true or false"));
}

std::string ParamReader::text(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  XmlRpc::XmlRpcValue& v = tree_[key];
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) return static_cast<std::string>(v);
  throw ParameterError(type_error(where(key), v, "a string"));
}

void ParamReader::check_unknown() const {
  if (tree_.getType() != XmlRpc::XmlRpcValue::TypeStruct) return;
  XmlRpc::XmlRpcValue copy = tree_;  // XmlRpcValue iterates only when non-const
  for (auto& kv : copy) {
    if (known_.count(kv.first)) continue;
    throw ParameterError(ns_ + "/" + kv.first +
                         ": unknown parameter (the scene's keys go under " + ns_ + "/scene or in " + ns_ +
                         "/scene_file; the node's parameters are listed in docs/ros.md)");
  }
}

namespace {

// What rviz shows: markers, trail, grid.
void read_display_parameters(ParamReader& p, NodeParameters& n) {
  n.trail_seconds = p.number("trail_seconds", n.trail_seconds);
  require(std::isfinite(n.trail_seconds) && n.trail_seconds > 0.0, p.where("trail_seconds"), n.trail_seconds,
          "> 0 s");
  n.path_length = p.integer("path_length", n.path_length);
  require(n.path_length >= 2, p.where("path_length"), n.path_length, ">= 2 (poses at most per trail)");
  n.path_resolution = p.number("path_resolution", n.path_resolution);
  require(std::isfinite(n.path_resolution) && n.path_resolution >= 0.0, p.where("path_resolution"),
          n.path_resolution, ">= 0 m");
  n.marker_rate = p.number("marker_rate", n.marker_rate);
  require(std::isfinite(n.marker_rate) && n.marker_rate > 0.0, p.where("marker_rate"), n.marker_rate, "> 0 Hz");
  n.marker_refresh = p.number("marker_refresh", n.marker_refresh);
  require(std::isfinite(n.marker_refresh) && n.marker_refresh > 0.0, p.where("marker_refresh"), n.marker_refresh,
          "> 0 s");
  n.path_rate = p.number("path_rate", n.path_rate);
  require(std::isfinite(n.path_rate) && n.path_rate > 0.0, p.where("path_rate"), n.path_rate, "> 0 Hz");
  const std::string color_by = p.text("color_by", "regime");
  if (!parse_color_by(color_by, n.color_by))
    throw ParameterError(p.where("color_by") + " = '" + color_by + "': must be one of regime, mode");
  n.grid_pitch = p.number("grid_pitch", n.grid_pitch);
  require(std::isfinite(n.grid_pitch) && n.grid_pitch > 0.0, p.where("grid_pitch"), n.grid_pitch, "> 0 m");
  n.grid_cells = p.integer("grid_cells", n.grid_cells);
  require(n.grid_cells >= 1 && n.grid_cells <= 1000, p.where("grid_cells"), n.grid_cells, "in [1, 1000]");
}

}  // namespace

int read_cpu_affinity(ParamReader& p) {
  const int cpu = p.integer("cpu_affinity", kNoCpuAffinity);
  const std::string error = check_cpu_affinity(p.where("cpu_affinity"), cpu, online_cpus());
  if (!error.empty()) throw ParameterError(error);
  return cpu;
}

NodeParameters read_node_parameters(ParamReader& p) {
  NodeParameters n;
  n.publish_rate = p.number("publish_rate", n.publish_rate);
  require(std::isfinite(n.publish_rate) && n.publish_rate > 0.0 && n.publish_rate <= kMaxPublishRate,
          p.where("publish_rate"), n.publish_rate, "in (0, 10000] Hz");
  n.real_time_factor = p.number("real_time_factor", n.real_time_factor);
  require(std::isfinite(n.real_time_factor) && n.real_time_factor >= 0.0, p.where("real_time_factor"),
          n.real_time_factor, ">= 0 and finite (0 = as fast as possible)");
  n.publish_clock = p.flag("publish_clock", n.publish_clock);
  n.publish_tf = p.flag("publish_tf", n.publish_tf);
  n.frames.world = p.text("world_frame", n.frames.world);
  n.frames.plane = p.text("plane_frame", n.frames.plane);
  n.frames.top = p.text("top_frame", n.frames.top);
  n.frames.contact = p.text("contact_frame", n.frames.contact);
  n.frames.grid = p.text("grid_frame", n.frames.grid);
  n.follow_frame = p.text("follow_frame", n.follow_frame);
  n.follow = p.text("follow", n.follow);
  read_display_parameters(p, n);
  n.path_resolution = p.number("path_resolution", n.path_resolution);
  n.lcm_url = p.text("lcm_url", n.lcm_url);
  n.lcm_channel = p.text("lcm_channel", n.lcm_channel);
  n.config_dir = p.text("config_dir", n.config_dir);
  n.cpu_affinity = read_cpu_affinity(p);
  n.topics_at_start = p.integer("topics_at_start", n.topics_at_start);
  require(n.topics_at_start >= -1, p.where("topics_at_start"), n.topics_at_start,
          ">= 0 tops, or -1 = all (the launch-time top's are always there)");
  if (p.has("per_top_topics"))  // a string or a number is refused by flag(): "must be true or false"
    n.per_top_topics = p.flag("per_top_topics", true) ? PerTopTopics::on : PerTopTopics::off;
  return n;
}

bool own_topics(PerTopTopics rule, std::size_t tops) {
  if (rule == PerTopTopics::by_count) return tops <= kPerTopTopicsUpTo;
  return rule == PerTopTopics::on;
}

top_sim::Scene scene_value(XmlRpc::XmlRpcValue& value, const std::string& source, const std::string& config_dir,
                           const top_sim::Scene& fallback) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    const std::string text = static_cast<std::string>(value);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) return fallback;
    return top_sim::parse_scene_text(text, source, config_dir);
  }
  if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct)
    return top_sim::parse_scene(to_yaml(value, source), source, config_dir);
  throw ParameterError(type_error(source, value, "scene YAML text or a map of scene keys"));
}

std::string default_scene_file(const std::string& config_dir) { return config_dir + "/scenes/default.yaml"; }

top_sim::Scene read_node_scene(ParamReader& p, const std::string& config_dir) {
  const std::string file = p.text("scene_file", "");
  const bool inline_scene = p.has("scene");
  if (!file.empty() && inline_scene)
    throw ParameterError("the scene comes from one place: " + p.where("scene_file") + " = '" + file + "' and " +
                         p.where("scene") + " are both set; keep one");
  // roslaunch runs the node in ~/.ros: a relative path is the caller's, whose directory top_sim.launch passes.
  const std::string caller_dir = p.text("caller_dir", "");
  if (!file.empty()) return top_sim::load_scene(top_sim::scene_path(file, config_dir, caller_dir));
  if (!inline_scene) {
    if (config_dir.empty())
      throw ParameterError("no scene: set " + p.where("scene_file") + " (a scene file) or " + p.where("scene") +
                           " (scene YAML text or keys)");
    return top_sim::load_scene(default_scene_file(config_dir));  // as turtlesim starts with one turtle
  }
  const top_sim::Scene none;
  XmlRpc::XmlRpcValue& v = p.raw("scene");
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString && static_cast<std::string>(v).empty())
    throw ParameterError(p.where("scene") + " is empty: give scene YAML text or keys");
  return scene_value(v, p.where("scene"), config_dir, none);
}

std::vector<std::pair<std::string, top_sim::Scene>> read_start_tops(ParamReader& p, const std::string& config_dir,
                                                                     const top_sim::Scene& node_scene) {
  std::vector<std::pair<std::string, top_sim::Scene>> tops;
  if (!p.has("tops")) return tops;
  XmlRpc::XmlRpcValue& v = p.raw("tops");
  if (v.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    throw ParameterError(type_error(p.where("tops"), v, "a map NAME: scene (YAML text, \"\" = the node's scene)"));
  for (auto& kv : v)  // XmlRpc's struct is a std::map: name order
    tops.emplace_back(kv.first, scene_value(kv.second, p.where("tops/" + kv.first), config_dir, node_scene));
  return tops;
}

}  // namespace top_sim_ros
