// Finds the data directory relative to the core library's own file (dladdr), as installed or built.
#include "top_sim/data_path.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "top_sim/scene_error.hpp"

#ifndef TOP_SIM_DATA_SUBDIR
#define TOP_SIM_DATA_SUBDIR "share/top_sim/config"
#endif

namespace top_sim {

namespace fs = std::filesystem;

namespace {

// The file this code was loaded from: the shared library, or the executable it was linked into ("" if unknown).
fs::path own_file() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_config_dir), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code ec;
  const fs::path path = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path() : path;
}

}  // namespace

std::string default_config_dir() {
  if (const char* env = std::getenv("TOP_SIM_CONFIG_DIR")) return env;
  // <prefix>/lib/libtop_sim_core.so, <prefix>/bin/tool or catkin's <prefix>/lib/top_sim/tool: up to 3 levels.
  fs::path dir = own_file().parent_path();
  for (int level = 0; level < 3 && !dir.empty(); ++level, dir = dir.parent_path()) {
    const fs::path candidate = dir / TOP_SIM_DATA_SUBDIR;
    std::error_code ec;
    if (fs::is_directory(candidate / "scenes", ec)) return candidate.string();
  }
  return "";
}

namespace {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> shipped_scene_names(const std::string& config_dir) {
  const fs::path scenes = fs::path(config_dir.empty() ? default_config_dir() : config_dir) / "scenes";
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(scenes, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".yaml" && it->is_regular_file(ec)) names.push_back(it->path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string scene_path(const std::string& name_or_path, const std::string& config_dir, const std::string& base_dir) {
  const std::string& arg = name_or_path;
  if (arg.find('/') != std::string::npos || ends_with(arg, ".yaml") || ends_with(arg, ".yml")) {
    const fs::path path(arg);
    return path.is_relative() && !base_dir.empty() ? (fs::path(base_dir) / path).string() : arg;
  }
  const std::string dir = config_dir.empty() ? default_config_dir() : config_dir;
  if (dir.empty())
    throw SceneError(arg, "", "names no scene file: a shipped scene's name needs the data directory, which was not "
                              "found (set TOP_SIM_CONFIG_DIR), or give a path to a scene file");
  const std::vector<std::string> shipped = shipped_scene_names(dir);
  if (std::find(shipped.begin(), shipped.end(), arg) == shipped.end())
    throw SceneError(arg, "", "no shipped scene has this name; the shipped scenes (" + dir + "/scenes) are: " +
                                  joined(shipped) + "; or give a path to a scene file (containing '/' or ending " +
                                  "in .yaml)");
  return dir + "/scenes/" + arg + ".yaml";
}

}  // namespace top_sim
