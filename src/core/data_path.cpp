// Finds the data directory relative to the core library's own file (dladdr), as installed or built.
#include "top_sim/data_path.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

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

}  // namespace top_sim
