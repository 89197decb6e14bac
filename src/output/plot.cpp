#include "plot.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "top_sim/data_path.hpp"

namespace top_sim_cli {

std::string plot_script(const std::string& name) {
  std::vector<std::string> candidates;
  if (const char* dir = std::getenv("TOP_SIM_PLOTS_DIR")) candidates.push_back(std::string(dir) + "/" + name);
  const std::string config = top_sim::default_config_dir();
  if (!config.empty()) {
    candidates.push_back(config + "/../plots/" + name);
    candidates.push_back(config + "/../scripts/plots/" + name);
  }
  for (const auto& c : candidates)
    if (std::filesystem::is_regular_file(c)) return c;
  return "";
}

bool run_plot(const std::string& tool, const std::string& name, const std::vector<std::string>& args,
              const std::string& png) {
  const std::string script = plot_script(name);
  if (script.empty()) {
    std::cerr << tool << ": --plot = '" << png << "': scripts/plots/" << name
              << " not found (set TOP_SIM_PLOTS_DIR to the directory holding it)\n";
    return false;
  }
  // Debian's python3 has python3-matplotlib; a python3 first on PATH (pyenv, conda) may lack it.
  const char* chosen = std::getenv("TOP_SIM_PYTHON");
  const std::string python = chosen                                        ? chosen
                             : std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3"
                                                                           : "python3";
  std::vector<std::string> words = {python, script};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::cout.flush();
  pid_t pid;
  int status = 0;
  if (posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0 || waitpid(pid, &status, 0) < 0 ||
      !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << tool << ": --plot = '" << png << "': " << python << " " << script
              << " failed (is python3-matplotlib installed? TOP_SIM_PYTHON names another interpreter)\n";
    return false;
  }
  return true;
}

}  // namespace top_sim_cli
