// Numbers in messages: the shortest text that reads back as the same double (exact, and 1.6 stays "1.6").
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <string>

namespace top_sim {

// A NaN is "nan" whatever its sign bit (to_chars writes "-nan" for some, which reads as a negative number).
inline std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
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
