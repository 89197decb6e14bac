// Command-line arguments of the tools: one error type and one exit path for usage and bad arguments (the tools read
// their command lines with CommandLine, command_line.hpp).
#pragma once

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace top_sim_cli {

// A bad command-line argument; the message names the argument, its value and the allowed range.
struct BadArgument {
  std::string message;
};

// `text` as a finite number; throws naming the flag and the text otherwise.
inline double finite_number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw BadArgument{flag + " = '" + text + "': not a finite number"};
  return v;
}

// The tool's one positional argument (`what`: "scene file", "bag"); throws when none (an empty one is none) or
// more than one was given.
inline std::string one_positional(const std::vector<std::string>& given, const std::string& what) {
  if (given.empty() || (given.size() == 1 && given[0].empty())) throw BadArgument{"no " + what + " given"};
  if (given.size() > 1) throw BadArgument{"more than one " + what + " ('" + given[0] + "', '" + given[1] + "')"};
  return given[0];
}

// Runs parse(argc, argv, args), which returns false when it was asked for help. The exit status when the tool is
// done (0 after the usage, 2 after the message and the usage of a bad argument), or nothing to go on.
template <class Arguments, class Parse>
std::optional<int> parse_command_line(const char* tool, const char* usage, Parse parse, int argc, char** argv,
                                      Arguments& args) {
  try {
    if (parse(argc, argv, args)) return std::nullopt;
    std::cout << usage;
    return 0;
  } catch (const BadArgument& e) {
    std::cerr << tool << ": " << e.message << "\n" << usage;
    return 2;
  }
}

}  // namespace top_sim_cli
