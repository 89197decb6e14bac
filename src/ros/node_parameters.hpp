// The node's parameters under ~ and the scenes it starts with (docs/ros.md, "Parameters"). Everything is read from
// one snapshot of the private namespace with strict types, so a wrong type or an unknown key is an error naming the
// parameter, never a silent default.
#pragma once

#include <cstddef>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include <xmlrpcpp/XmlRpcValue.h>

#include "conversions.hpp"
#include "markers.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"

namespace top_sim_ros {

// A bad parameter: the message names it (with its namespace), its value and the allowed range.
class ParameterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads typed values from the private namespace's tree and remembers every key it was asked for, so the keys the
// node knows are exactly the keys it reads (no hand-written list to fall out of date).
class ParamReader {
 public:
  ParamReader(XmlRpc::XmlRpcValue tree, std::string ns);
  double number(const std::string& key, double fallback);  // an int or a double
  int integer(const std::string& key, int fallback);
  bool flag(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  bool has(const std::string& key);
  XmlRpc::XmlRpcValue& raw(const std::string& key);  // has(key) must hold
  void know(const std::string& key) { known_.insert(key); }
  // Throws ParameterError for a key under ~ that nobody read.
  void check_unknown() const;
  XmlRpc::XmlRpcValue& tree() { return tree_; }
  std::string where(const std::string& key) const { return ns_ + "/" + key; }

 private:
  XmlRpc::XmlRpcValue tree_;
  std::string ns_;
  std::set<std::string> known_;
};

// ~per_top_topics: whether a spawned top gets its own five topics (NAME/top_state, NAME/path, NAME/inclination,
// NAME/spin, NAME/command); every top is on ~top_states and ~tops/command anyway. Unset: by the node's count.
enum class PerTopTopics { by_count, on, off };
constexpr std::size_t kPerTopTopicsUpTo = 100;  // by_count: on while the node has at most this many tops

// Whether a top gets its own topics under `rule` when the node will hold `tops` tops (the new ones counted).
bool own_topics(PerTopTopics rule, std::size_t tops);

struct NodeParameters {
  double publish_rate = 200.0;      // [Hz], in (0, kMaxPublishRate]
  double real_time_factor = 1.0;    // >= 0, 0 = as fast as possible
  bool publish_clock = false;       // /clock from the launch-time top's stamps
  bool publish_tf = true;           // tf for every top (off for thousands of tops watched through top_states)
  Frames frames;                    // the launch-time top's; a spawned top NAME uses NAME/<plane>, NAME/<top>, ...
  std::string follow_frame = "follow";  // at the followed top's contact point, plane axes (the camera's target)
  std::string follow;               // the top it follows ("" = the launch-time top)
  double trail_seconds = 60.0;      // [s] of simulated time the trail covers
  int path_length = 1000;           // poses at most per trail: beyond, its oldest chunks are merged (coverage kept)
  double path_resolution = 2.0e-4;  // [m] between poses
  double marker_rate = 10.0;        // [Hz]
  double marker_refresh = 10.0;     // [s] every marker is sent again at least this often (a bag from any moment)
  double path_rate = 0.1;           // [Hz]
  ColorBy color_by = ColorBy::regime;
  double grid_pitch = 0.05;         // [m]
  int grid_cells = 40;
  std::string lcm_url, lcm_channel = "TOP_STATE";
  std::string config_dir;           // where scenes find tops/ and planes/
  int cpu_affinity = -1;            // the CPU all the node's threads run on; -1 = not pinned (cpu_affinity.hpp)
  // Tops (the launch-time top counted) whose own topics exist before the loop starts; the others' are opened on a
  // background thread (topic_opener.hpp); -1 = all before the loop.
  int topics_at_start = 100;
  PerTopTopics per_top_topics = PerTopTopics::by_count;
};

constexpr double kMaxPublishRate = 10000.0;

// "NAME = VALUE: must be RANGE".
std::string range_error(const std::string& name, double value, const std::string& range);

// ~cpu_affinity: -1 (the default) or a CPU online; throws ParameterError. Read on its own too, before roscpp starts.
int read_cpu_affinity(ParamReader& params);

// The node's own parameters; throws ParameterError.
NodeParameters read_node_parameters(ParamReader& params);

// The launch-time scene: ~scene_file (a file or a shipped scene's name, top_sim::scene_path, read by load_scene as
// top_sim_run reads it; a relative path is taken from ~caller_dir when set) or ~scene (YAML text, read
// with the same checks; or a map of parameters, which rosparam has already de-duplicated). At most one of them;
// neither = the default scene of `config_dir` (an error when config_dir is empty).
// Throws top_sim::SceneError (bad scene) or ParameterError (bad source).
top_sim::Scene read_node_scene(ParamReader& params, const std::string& config_dir);
std::string default_scene_file(const std::string& config_dir);  // config_dir/scenes/default.yaml

// A scene given as a parameter value: YAML text (parse_scene_text: the file loader's checks; "" = `fallback`) or a
// map of parameters (parse_scene). `source` names it in messages.
top_sim::Scene scene_value(XmlRpc::XmlRpcValue& value, const std::string& source, const std::string& config_dir,
                           const top_sim::Scene& fallback);

// ~tops: extra tops at start, a map NAME -> scene (as scene_value reads it, "" = the node's scene), in name order;
// the caller spawns them exactly as the spawn service would.
std::vector<std::pair<std::string, top_sim::Scene>> read_start_tops(ParamReader& params, const std::string& config_dir,
                                                                     const top_sim::Scene& node_scene);

}  // namespace top_sim_ros
