// Numbers in messages: the shortest text that reads back as the same double (exact, and 1.6 stays "1.6").
#pragma once

#include <charconv>
#include <string>

namespace top_sim {

inline std::string format_number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace top_sim
