// Numbers in messages: the shortest text that reads back as the same double (exact, and 1.6 stays "1.6").
#pragma once

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cmath>
#include <optional>
#include <string>

namespace top_sim {

// Room a number's text takes at most (a double's shortest round-trip text is at most 24 characters).
constexpr std::size_t kNumberChars = 24;

// Writes v's shortest round-trip text at `first` (room for kNumberChars) and returns its end. A NaN is "nan"
// whatever its sign bit (to_chars writes "-nan" for some, which reads as a negative number).
inline char* put_number(char* first, double v) {
  if (std::isnan(v)) return std::copy_n("nan", 3, first);
  return std::to_chars(first, first + kNumberChars, v).ptr;
}

inline std::string format_number(double v) {
  char buf[kNumberChars];
  return std::string(buf, put_number(buf, v));
}

// The one form of a range error: "FIELD = VALUE: must be RANGE".
inline std::string range_message(const std::string& field, double value, const std::string& range) {
  return field + " = " + format_number(value) + ": must be " + range;
}

// The number a whole text spells (from_chars: no locale, no leading space, nothing after it), or nothing.
inline std::optional<double> parse_number(const std::string& text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, v);
  if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return v;
}

}  // namespace top_sim
