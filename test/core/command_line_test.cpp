// The tools' command lines through CLI11 (src/output/command_line.hpp) and their JSON through nlohmann-json
// (src/output/writers.cpp): the project's messages for what CLI11 refuses, the order values are read in, and a
// summary whose every number reads back as the same double.
// Boost 1.74's property_tree pulls in boost/bind.hpp, which otherwise warns about its global placeholders.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#include <gtest/gtest.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/output/arguments.hpp"
#include "../../src/output/command_line.hpp"
#include "../../src/output/writers.hpp"
#include "test_util.hpp"

namespace {

using top_sim_cli::BadArgument;
using top_sim_cli::CommandLine;

// What a tool with --x VALUE, --q and positionals reads from `args`.
struct Read {
  std::vector<std::string> x, positional;
  int q = 0;
  bool go_on = true;
  std::string refusal;  // the BadArgument's message, "" when none
};

Read read(const std::vector<std::string>& args, const std::string& unknown = "unknown option") {
  Read r;
  CommandLine line(unknown);
  line.value("--x", [&r](const std::string& v) {
        if (v == "bad") throw BadArgument{"--x = 'bad': must be good"};
        r.x.push_back(v);
      })
      .flag("--q", [&r] { ++r.q; })
      .positionals(r.positional);
  try {
    r.go_on = line.parse(args);
  } catch (const BadArgument& e) {
    r.refusal = e.message;
  }
  return r;
}

TEST(CommandLine, ReadsValuesFlagsAndPositionalsInOrder) {
  const Read r = read({"a", "--x", "1", "--q", "b", "--x=2", "--x", "-3"});
  EXPECT_EQ(r.refusal, "");
  EXPECT_TRUE(r.go_on);
  EXPECT_EQ(r.x, (std::vector<std::string>{"1", "2", "-3"}));  // each occurrence, a negative number a value
  EXPECT_EQ(r.positional, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(r.q, 1);
  // The value is the next argument whatever it looks like, as the hand-made parsers took it.
  EXPECT_EQ(read({"--x", "--q"}).x, (std::vector<std::string>{"--q"}));
}

TEST(CommandLine, RefusalsAreTheProjectsMessages) {
  EXPECT_EQ(read({"a", "--x"}).refusal, "--x: needs a value");
  EXPECT_EQ(read({"a", "--frobnicate"}).refusal, "unknown option '--frobnicate'");
  EXPECT_EQ(read({"a", "-f"}).refusal, "unknown option '-f'");
  EXPECT_EQ(read({"-1"}).refusal, "unknown option '-1'");  // a positional never starts with '-'
  EXPECT_EQ(read({"--frobnicate"}, "unknown argument").refusal, "unknown argument '--frobnicate'");
  EXPECT_EQ(read({"--x", "bad"}).refusal, "--x = 'bad': must be good");
  // Values are checked while reading: the first bad one is named, a later one is not read.
  EXPECT_EQ(read({"--x", "bad", "--x", "1"}).x.size(), 0u);
  EXPECT_EQ(read({"--x", "1", "--x", "bad"}).refusal, "--x = 'bad': must be good");
  // A flag given a word that is no truth value: CLI11's message, one line, naming the flag and the word.
  const std::string m = read({"--q=abc"}).refusal;
  EXPECT_NE(m.find("--q"), std::string::npos) << m;
  EXPECT_NE(m.find("abc"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(CommandLine, HelpStopsReadingWhereItStands) {
  EXPECT_FALSE(read({"-h"}).go_on);
  EXPECT_FALSE(read({"a", "--help", "--x", "bad"}).go_on);  // nothing after it is read
  EXPECT_EQ(read({"--x", "bad", "--help"}).refusal, "--x = 'bad': must be good");
  EXPECT_EQ(read({"--x", "--help"}).x, (std::vector<std::string>{"--help"}));  // a value, not the flag
}

TEST(CommandLine, OnePositionalNamesWhatIsMissingOrTooMuch) {
  EXPECT_EQ(top_sim_cli::one_positional({"a"}, "scene file"), "a");
  for (const std::vector<std::string>& none : {std::vector<std::string>{}, std::vector<std::string>{""}}) {
    try {
      top_sim_cli::one_positional(none, "scene file");
      FAIL() << "none accepted";
    } catch (const BadArgument& e) {
      EXPECT_EQ(e.message, "no scene file given");
    }
  }
  try {
    top_sim_cli::one_positional({"a", "b"}, "scene file");
    FAIL() << "two accepted";
  } catch (const BadArgument& e) {
    EXPECT_EQ(e.message, "more than one scene file ('a', 'b')");
  }
}

namespace pt = boost::property_tree;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every number of a run's summary, read back by another library (Boost's), is the run's double in every bit: the
// shortest text that reads back as the same double loses nothing (docs/interfaces.md, issue 33).
TEST(SummaryJson, NumbersReadBackAsTheSameDoubles) {
  top_sim::Simulator sim(top_sim::load_scene(top_sim_test::scene_path("hopping")));
  top_sim::RunOptions opt;
  opt.duration = 0.3;
  top_sim::RunResult r = top_sim::run(sim, opt);
  ASSERT_FALSE(r.mode_switches.empty()) << "the hopping top lifts off within 0.3 s";
  r.cpu_seconds = 0.0;  // real_time_factor not finite: null
  std::istringstream in(top_sim::summary_json(sim.scene(), r));
  pt::ptree j;
  ASSERT_NO_THROW(pt::read_json(in, j));
  EXPECT_EQ(j.get<std::string>("real_time_factor"), "null");  // Boost keeps null as its text
  const top_sim::Snapshot& f = r.final;
  const std::pair<const char*, double> scalars[] = {
      {"sim_seconds", r.sim_seconds}, {"energy_balance_residual", r.max_energy_residual}, {"final.t", f.t},
      {"final.spin", f.spin}, {"final.slip", f.slip}, {"final.phi", f.phi},
      {"mode_seconds.flight", r.mode_seconds[static_cast<std::size_t>(top_sim::ContactMode::flight)]}};
  for (const auto& [key, value] : scalars) EXPECT_TRUE(same_bits(j.get<double>(key), value)) << key;
  std::vector<double> omega;
  for (const auto& kv : j.get_child("final.omega")) omega.push_back(kv.second.get_value<double>());
  ASSERT_EQ(omega.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(omega[i], f.angular_velocity[i])) << "omega " << i;
  const pt::ptree& first = j.get_child("mode_switches").begin()->second;
  EXPECT_TRUE(same_bits(first.get<double>("t"), r.mode_switches[0].t));
  EXPECT_TRUE(same_bits(first.get<double>("energy_change"), r.mode_switches[0].energy_change));
}

}  // namespace
