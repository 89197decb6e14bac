// Finds the data directory relative to the core library's own file (dladdr), as installed or built.
#include "top_sim/data_path.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdlib>

#ifndef TOP_SIM_DATA_SUBDIR
#define TOP_SIM_DATA_SUBDIR "share/top_sim/config"
#endif

namespace top_sim {

namespace {

bool is_dir(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string parent(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos || slash == 0 ? std::string() : path.substr(0, slash);
}

// The file this code was loaded from: the shared library, or the executable it was linked into.
std::string own_file() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_config_dir), &info) == 0 || info.dli_fname == nullptr) return "";
  char* resolved = realpath(info.dli_fname, nullptr);
  if (resolved == nullptr) return "";
  std::string path(resolved);
  std::free(resolved);
  return path;
}

}  // namespace

std::string default_config_dir() {
  if (const char* env = std::getenv("TOP_SIM_CONFIG_DIR")) return env;
  // <prefix>/lib/libtop_sim_core.so, <prefix>/bin/tool or catkin's <prefix>/lib/top_sim/tool: up to 3 levels.
  std::string dir = parent(own_file());
  for (int level = 0; level < 3 && !dir.empty(); ++level, dir = parent(dir)) {
    const std::string candidate = dir + "/" + TOP_SIM_DATA_SUBDIR;
    if (is_dir(candidate + "/scenes")) return candidate;
  }
  return "";
}

}  // namespace top_sim
