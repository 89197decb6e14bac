// Where the installed data (config/: tops, planes, scenes) is found: never by a compiled-in source path.
#pragma once

#include <string>

namespace top_sim {

// The directory holding tops/, planes/ and scenes/: $TOP_SIM_CONFIG_DIR if set, else share/top_sim/config next
// to the directory of the core library (build and install trees have the same layout); "" if neither exists.
std::string default_config_dir();

}  // namespace top_sim
