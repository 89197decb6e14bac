// A tool's command line read by CLI11 (libcli11-dev) with the project's own words: each tool prints its own usage
// text for -h/--help, and every refusal is a top_sim_cli::BadArgument (arguments.hpp) naming the argument, its
// value and the allowed range. CLI11 stays behind this class: no tool's header includes it.
#pragma once

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace top_sim_cli {

class CommandLine {
 public:
  // `unknown`: how a refusal names an argument the tool does not take ("unknown option", "unknown argument").
  explicit CommandLine(std::string unknown = "unknown option");
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  // FLAG takes the next argument as its value, whatever it looks like; `read` checks and stores it (throws
  // BadArgument). A flag given twice is read twice, in order: the last value stays.
  CommandLine& value(const std::string& flag, std::function<void(const std::string&)> read);
  // FLAG takes no value.
  CommandLine& flag(const std::string& flag, std::function<void()> set);
  // The arguments that are no option, in their order (without this, each is refused as unknown; one that starts
  // with '-' always is).
  CommandLine& positionals(std::vector<std::string>& out);

  // Reads `args` (no program name) in order; false when -h or --help came before any bad argument. Throws
  // BadArgument: the option's own message, "FLAG: needs a value", or "UNKNOWN 'ARG'".
  bool parse(const std::vector<std::string>& args);
  bool parse(int argc, char** argv) { return parse(std::vector<std::string>(argv + 1, argv + argc)); }

 private:
  std::unique_ptr<CLI::App> app_;
  std::string unknown_;
  std::set<std::string> takes_value_;
  const std::vector<std::string>* positionals_ = nullptr;
};

}  // namespace top_sim_cli
