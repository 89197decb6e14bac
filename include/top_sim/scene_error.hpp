// A bad scene (docs/interfaces.md): the error every scene reader throws, naming file, key, value and range. Its own
// header so the data directory's lookup (data_path.cpp) can refuse a scene name without including the loader.
#pragma once

#include <stdexcept>
#include <string>

namespace top_sim {

// A bad scene: names the file, key, value and allowed range.
class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& file, const std::string& key, const std::string& problem);
  std::string file, key;
};

}  // namespace top_sim
