// Where the installed data (config/: tops, planes, scenes) is found: never by a compiled-in source path.
#pragma once

#include <string>
#include <vector>

namespace top_sim {

// The directory holding tops/, planes/ and scenes/: $TOP_SIM_CONFIG_DIR if set, else share/top_sim/config next
// to the directory of the core library (build and install trees have the same layout); "" if neither exists.
std::string default_config_dir();

// The shipped scenes: the names of <config_dir>/scenes/*.yaml without ".yaml", sorted ("" = default_config_dir()).
std::vector<std::string> shipped_scene_names(const std::string& config_dir = "");

// The one rule for what names a scene (top_sim_run's argument, the node's ~scene_file, top_sim.launch's scene:=):
// a path when it contains '/' or ends in .yaml or .yml (a relative path is taken from `base_dir` when that is not
// empty: the caller's directory, for a node that runs elsewhere); otherwise the name of a shipped scene,
// <config_dir>/scenes/NAME.yaml. A name that is no shipped scene: SceneError listing the shipped ones.
std::string scene_path(const std::string& name_or_path, const std::string& config_dir = "",
                       const std::string& base_dir = "");

}  // namespace top_sim
