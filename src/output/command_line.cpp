#include "command_line.hpp"

#include <CLI/CLI.hpp>

#include <utility>

#include "arguments.hpp"

namespace top_sim_cli {

namespace {

// Thrown by -h/--help when it is read: the arguments after it are not looked at, as before CLI11.
struct HelpAsked {};

}  // namespace

CommandLine::CommandLine(std::string unknown) : app_(std::make_unique<CLI::App>()), unknown_(std::move(unknown)) {
  app_->set_help_flag();      // the tool prints its own usage text
  app_->allow_extras();       // unknown arguments are refused below, in the project's words
  app_->add_flag_callback("-h,--help", [] { throw HelpAsked{}; })->trigger_on_parse();
}

CommandLine::~CommandLine() = default;

CommandLine& CommandLine::value(const std::string& flag, std::function<void(const std::string&)> read) {
  // Read on parse: each occurrence in order, so the first bad value is the one named.
  app_->add_option_function<std::string>(flag, std::move(read))->trigger_on_parse();
  takes_value_.insert(flag);
  return *this;
}

CommandLine& CommandLine::flag(const std::string& flag, std::function<void()> set) {
  app_->add_flag_callback(flag, std::move(set))->trigger_on_parse();
  return *this;
}

CommandLine& CommandLine::positionals(std::vector<std::string>& out) {
  app_->add_option("arguments", out);
  positionals_ = &out;
  return *this;
}

bool CommandLine::parse(const std::vector<std::string>& args) {
  std::vector<std::string> last_first(args.rbegin(), args.rend());  // CLI11 pops its arguments from the back
  try {
    app_->parse(last_first);
  } catch (const HelpAsked&) {
    return false;
  } catch (const CLI::ArgumentMismatch& e) {
    // A flag that takes a value can only lack it at the end: the last argument is that flag.
    if (!args.empty() && takes_value_.count(args.back())) throw BadArgument{args.back() + ": needs a value"};
    throw BadArgument{e.what()};
  } catch (const CLI::ParseError& e) {
    // e.g. a flag given a word that is no truth value (--quiet=abc): CLI11's own one-line message
    throw BadArgument{e.what()};
  }
  if (const std::vector<std::string> rest = app_->remaining(); !rest.empty())
    throw BadArgument{unknown_ + " '" + rest.front() + "'"};
  if (positionals_)  // what CLI11 takes for a value ("-1", "---", "-") is no tool's positional argument either
    for (const std::string& a : *positionals_)
      if (!a.empty() && a[0] == '-') throw BadArgument{unknown_ + " '" + a + "'"};
  return true;
}

}  // namespace top_sim_cli
