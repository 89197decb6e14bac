// A bad scene's message: file and key first, control characters escaped.
#include "top_sim/scene_error.hpp"

namespace top_sim {

namespace {

// Keys and values are quoted in messages: control characters appear escaped (a NUL cut what() short), e.g. \x00.
std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out += c;
    } else {
      static const char hex[] = "0123456789abcdef";
      out += {'\\', 'x', hex[u >> 4], hex[u & 0xf]};
    }
  }
  return out;
}

}  // namespace

SceneError::SceneError(const std::string& f, const std::string& k, const std::string& problem)
    : std::runtime_error(printable(f + ": " + (k.empty() ? "" : k + ": ") + problem)), file(f), key(k) {}

}  // namespace top_sim
