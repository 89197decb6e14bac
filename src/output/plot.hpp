// The command-line tools' --plot: a Python/matplotlib script of scripts/plots run on data the tool wrote.
#pragma once

#include <string>
#include <vector>

namespace top_sim_cli {

// scripts/plots/NAME: $TOP_SIM_PLOTS_DIR, else share/top_sim/plots next to the data (install tree, and the build
// tree's link), else the sources' scripts/plots. "" when not found.
std::string plot_script(const std::string& name);

// Runs `python3 SCRIPT ARGS...` (python3: $TOP_SIM_PYTHON, else /usr/bin/python3, which has Debian's matplotlib,
// else python3 on PATH). False, after a message naming `tool` and the PNG, when the script is missing or fails.
bool run_plot(const std::string& tool, const std::string& name, const std::vector<std::string>& args,
              const std::string& png);

}  // namespace top_sim_cli
