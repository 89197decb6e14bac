// top_sim_bag BAG [options]: the TopStates of a rosbag as top_sim_run's CSV, summary JSON and plot (see kUsage and
// docs/interfaces.md). Exit 0 ok, 1 an output not written, 2 bad argument, bag, topic, --top, scene or message.
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "command_line.hpp"
#include "conversions.hpp"
#include "plot.hpp"
#include "writers.hpp"
#include "top_sim/TopState.h"
#include "top_sim/TopStateArray.h"
#include "top_sim/format.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/scene.hpp"

namespace {

const char* kUsage =
    "usage: top_sim_bag BAG [--top NAME] [--csv FILE] [--json FILE|-] [--plot FILE.png] [--scene FILE]\n"
    "                   [--from T0] [--to T1]\n"
    "  Reads every top_sim/TopState topic of BAG: /NS/top_state is the top NS (a node's launch-time top),\n"
    "  /NS/NAME/top_state the top NAME; and every top in a top_sim/TopStateArray topic (/NS/top_states) that\n"
    "  has no TopState topic of its own in BAG (the array's first and last messages name them; --top finds any).\n"
    "  With several tops each output is written per top, FILE's name + _NAME.\n"
    "  --top NAME      only this top (its name or its topic)\n"
    "  --csv FILE      top_sim_run's CSV columns, t = TopState.sim_time\n"
    "  --json FILE     the summary (- for standard output; one top only)\n"
    "  --plot FILE.png contact-point path, phi(t) against phi*, energy residual (python3 with matplotlib)\n"
    "  --scene FILE    phi_star from this scene's stationary solver (else the last TopState's phi_star)\n"
    "  --from T0       first sim_time kept [s] (a ~reset restarts the motion while t runs on)\n"
    "  --to T1         last sim_time kept [s]\n"
    "Exit status: 0 ok; 1 an output not written; 2 bad argument, bag, topic, --top, scene or message.\n";

constexpr const char* kTool = "top_sim_bag";
using top_sim_cli::BadArgument;

// Bad input found after the arguments (bag, topic, message, scene): exit 2 with the message.
struct BadInput {
  std::string message;
};

struct Arguments {
  std::string bag, top, csv, json, plot, scene;
  double from = -std::numeric_limits<double>::infinity(), to = std::numeric_limits<double>::infinity();
};

double number(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v))
    throw BadArgument{flag + " = '" + value + "': must be a finite number of seconds"};
  return v;
}

// A non-empty text value.
std::string text(const std::string& flag, const std::string& value) {
  if (value.empty()) throw BadArgument{flag + " = '': must not be empty"};
  return value;
}

// Reads the command line (throws BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  std::vector<std::string> bags;
  top_sim_cli::CommandLine line;
  for (auto [flag, slot] : {std::pair{"--top", &args.top}, {"--csv", &args.csv}, {"--json", &args.json},
                            {"--plot", &args.plot}, {"--scene", &args.scene}})
    line.value(flag, [flag = std::string(flag), slot = slot](const std::string& v) { *slot = text(flag, v); });
  line.value("--from", [&](const std::string& v) { args.from = number("--from", v); })
      .value("--to", [&](const std::string& v) { args.to = number("--to", v); })
      .positionals(bags);
  if (!line.parse(argc, argv)) return false;
  args.bag = top_sim_cli::one_positional(bags, "bag");
  if (args.csv == "-")
    throw BadArgument{"--csv = '-': must be a file name (the CSV is not written to standard output)"};
  if (args.from > args.to)
    throw BadArgument{"--from " + top_sim::format_number(args.from) + " is after --to " +
                      top_sim::format_number(args.to) + ": must be <= --to"};
  return true;
}

struct Top {
  std::string name, topic;
  std::string entry;  // in a TopStateArray topic: the top's name in its `names`; "" for a TopState topic
};

constexpr const char* kLaunchTopName = "top";  // the node's name for its launch-time top (docs/ros.md, "Many tops")

// "/ns/top_state" -> "top" (a node's launch-time top, named as in the node's ~list), "/ns/NAME/top_state" ->
// "NAME"; another topic of the type (remapped) is named by its last part.
std::string short_name(const std::string& topic) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : topic + "/") {
    if (c != '/') { part += c; continue; }
    if (!part.empty()) parts.push_back(part);
    part.clear();
  }
  if (parts.size() == 2 && parts.back() == "top_state") return kLaunchTopName;
  if (parts.size() > 2 && parts.back() == "top_state") return parts[parts.size() - 2];
  return parts.empty() ? topic : parts.back();
}

// Tops whose short names collide are named by their whole namespace, '/' written '.' ("/a/x/top_state" -> "a.x";
// graph names have no '.', so these cannot collide).
std::string qualified_name(const std::string& topic) {
  std::string ns = topic.substr(topic.front() == '/' ? 1 : 0);
  const std::string suffix = "/top_state";
  if (ns.size() > suffix.size() && ns.compare(ns.size() - suffix.size(), suffix.size(), suffix) == 0)
    ns.resize(ns.size() - suffix.size());
  for (char& c : ns)
    if (c == '/') c = '.';
  return ns;
}

// The names in an array topic's first and last messages (a top spawned and killed between them is not listed; --top
// NAME reads it all the same), in the order of the first, then the last's new ones.
std::vector<std::string> array_names(rosbag::Bag& bag, const rosbag::ConnectionInfo& c) {
  rosbag::View view(bag, rosbag::TopicQuery(c.topic));
  std::vector<std::string> names;
  std::set<std::string> seen;
  const auto add = [&](const rosbag::MessageInstance& mi) {
    const top_sim::TopStateArray::ConstPtr m = mi.instantiate<top_sim::TopStateArray>();
    if (!m)
      throw BadInput{"topic " + c.topic + ": recorded with another TopStateArray definition (md5 " + mi.getMD5Sum() +
                     ", this build reads " + ros::message_traits::MD5Sum<top_sim::TopStateArray>::value() + ")"};
    for (const std::string& n : m->names)
      if (seen.insert(n).second) names.push_back(n);
  };
  if (view.size() == 0) return names;
  add(*view.begin());
  rosbag::View last(bag, rosbag::TopicQuery(c.topic), view.getEndTime(), view.getEndTime());
  if (last.size() > 0) add(*last.begin());
  return names;
}

// "/ns/top_states" -> "ns" ('/' written '.', as qualified_name does): names an array top whose name another has.
std::string array_namespace(const std::string& topic) {
  std::string ns = topic.substr(topic.front() == '/' ? 1 : 0);
  const std::string suffix = "top_states";
  if (ns.size() >= suffix.size() && ns.compare(ns.size() - suffix.size(), suffix.size(), suffix) == 0)
    ns.resize(ns.size() - suffix.size());
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  for (char& c : ns)
    if (c == '/') c = '.';
  return ns;
}

// The tops of the bag's array topics that no TopState topic of the bag carries (by short name).
void add_array_tops(rosbag::Bag& bag, const std::vector<const rosbag::ConnectionInfo*>& arrays,
                    std::map<std::string, int>& uses, std::vector<Top>& tops) {
  std::vector<Top> found;
  for (const rosbag::ConnectionInfo* c : arrays)
    for (const std::string& n : array_names(bag, *c))
      if (uses[n] == 0) found.push_back({n, c->topic, n});
  std::map<std::string, int> counts;
  for (const Top& t : found) ++counts[t.name];
  for (Top& t : found) {
    if (counts[t.name] > 1) t.name = array_namespace(t.topic) + "." + t.entry;  // two nodes' tops of one name
    tops.push_back(t);
  }
}

// The bag's tops: its top_sim/TopState topics, in topic order, then the tops only its TopStateArray topics carry;
// throws BadInput when there is none.
std::vector<Top> tops_in(rosbag::Bag& bag, std::vector<std::string>& array_topics_out) {
  rosbag::View view(bag);
  std::map<std::string, std::string> topics, others;  // topic -> short name; topic -> type
  std::map<std::string, int> uses;
  std::vector<const rosbag::ConnectionInfo*> arrays;
  std::set<std::string> array_topics;
  for (const rosbag::ConnectionInfo* c : view.getConnections()) {
    if (c->datatype == ros::message_traits::DataType<top_sim::TopStateArray>::value()) {
      if (array_topics.insert(c->topic).second) arrays.push_back(c);
    } else if (c->datatype != ros::message_traits::DataType<top_sim::TopState>::value()) {
      others.emplace(c->topic, c->datatype);
    } else if (topics.emplace(c->topic, short_name(c->topic)).second) {
      ++uses[short_name(c->topic)];
    }
  }
  std::vector<Top> tops;
  for (const auto& [topic, name] : topics) tops.push_back({uses[name] > 1 ? qualified_name(topic) : name, topic, ""});
  add_array_tops(bag, arrays, uses, tops);
  array_topics_out.assign(array_topics.begin(), array_topics.end());
  if (tops.empty()) {
    std::string list;
    for (const auto& [topic, type] : others) list += (list.empty() ? "" : ", ") + topic + " (" + type + ")";
    throw BadInput{"bag = '" + bag.getFileName() + "': no top_sim/TopState or TopStateArray topic; the bag has: " +
                   (list.empty() ? std::string("no messages") : list)};
  }
  return tops;
}

// The first array topic any of whose messages names `name` (a top spawned and killed between the first and last
// messages, which tops_in does not list), or "".
std::string array_with(rosbag::Bag& bag, const std::vector<std::string>& arrays, const std::string& name) {
  for (const std::string& topic : arrays) {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    for (const rosbag::MessageInstance& m : view) {
      const top_sim::TopStateArray::ConstPtr a = m.instantiate<top_sim::TopStateArray>();
      if (a && std::find(a->names.begin(), a->names.end(), name) != a->names.end()) return topic;
    }
  }
  return "";
}

// The tops to read: all, or the one --top names (by name or topic; or a name in an array topic's messages); throws
// BadInput for an unknown name.
std::vector<Top> select(rosbag::Bag& bag, const std::vector<Top>& tops, const std::vector<std::string>& arrays,
                        const std::string& wanted) {
  if (wanted.empty()) return tops;
  std::string known;
  for (const Top& t : tops) {
    if (t.name == wanted || (t.entry.empty() && t.topic == wanted)) return {t};
    known += (known.empty() ? "" : ", ") + t.name + " (" + t.topic + ")";
  }
  if (const std::string topic = array_with(bag, arrays, wanted); !topic.empty()) return {{wanted, topic, wanted}};
  const std::string bag_name = bag.getFileName();
  throw BadInput{"--top = '" + wanted + "': no such top in '" + bag_name + "'; its tops: " + known};
}

// FILE for one top; FILE's stem + "_" + NAME + its extension when there are several ("run.csv" -> "run_NAME.csv").
std::string output_path(const std::string& path, const Top& top, bool several) {
  if (path.empty() || !several) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "_" + top.name + p.extension().string())).string();
}

// Calls fn(snapshot) for each TopState of `topic` with sim_time in [from, to] that is later than the last one
// passed (a paused or faulted node repeats its instant); returns how many were skipped so. Throws BadInput for a
// message of another TopState definition or one that does not convert.
// The top's TopState in a message of its topic: the message itself, or its entry of an array (nullptr when this
// array does not carry the top). `index` keeps the entry's place from message to message.
const top_sim::TopState* state_of(const rosbag::MessageInstance& m, const Top& top, std::size_t& index,
                                  top_sim::TopState::ConstPtr& one, top_sim::TopStateArray::ConstPtr& array) {
  const bool in_array = !top.entry.empty();
  if (in_array ? !(array = m.instantiate<top_sim::TopStateArray>()) : !(one = m.instantiate<top_sim::TopState>())) {
    const std::string type = in_array ? "TopStateArray" : "TopState";
    const std::string md5 = in_array ? ros::message_traits::MD5Sum<top_sim::TopStateArray>::value()
                                     : ros::message_traits::MD5Sum<top_sim::TopState>::value();
    throw BadInput{"topic " + top.topic + ": recorded with another " + type + " definition (md5 " + m.getMD5Sum() +
                   ", this build reads " + md5 + ")"};
  }
  if (!in_array) return one.get();
  const std::size_t n = std::min(array->names.size(), array->states.size());
  if (index >= n || array->names[index] != top.entry) {  // the order changes only when tops come or go
    index = std::find(array->names.begin(), array->names.begin() + n, top.entry) - array->names.begin();
    if (index >= n) return nullptr;
  }
  return &array->states[index];
}

template <class Fn>
std::uint64_t for_each_state(rosbag::Bag& bag, const Top& top, const Arguments& args, Fn fn) {
  rosbag::View view(bag, rosbag::TopicQuery(top.topic));
  std::uint64_t skipped = 0;
  double last = -std::numeric_limits<double>::infinity();
  std::size_t index = 0;
  top_sim::TopState::ConstPtr one;
  top_sim::TopStateArray::ConstPtr array;
  const std::string& topic = top.topic;
  for (const rosbag::MessageInstance& m : view) {
    const top_sim::TopState* msg = state_of(m, top, index, one, array);
    if (!msg || msg->sim_time < args.from || msg->sim_time > args.to) continue;
    if (!(msg->sim_time > last)) {
      ++skipped;
      continue;
    }
    std::string error;
    const top_sim::Snapshot s = top_sim_ros::to_snapshot(*msg, error);
    if (!error.empty()) throw BadInput{"topic " + topic + ", message at bag time " +
                                       top_sim::format_number(m.getTime().toSec()) + " s: " + error};
    last = msg->sim_time;
    fn(s);
  }
  return skipped;
}

// phi_star and where it came from: the --scene's stationary solver at the last state's alpha and spin, else the
// last TopState's own (the node's solver at that state).
void set_phi_star(const top_sim::Scene* scene, const top_sim::Snapshot& last, top_sim::RecordedSource& src) {
  if (scene) {
    top_sim::Model model = scene->model;
    model.plane = top_sim::make_plane(last.alpha, model.plane.gravity);
    top_sim::set_phi_star(top_sim::stationary_state(model, last.spin), src.phi_star, src.stationary_note);
    src.phi_star_source = "the stationary solver of --scene " + scene->source + " at the last state's alpha and spin";
  } else {
    if (last.has_stationary_state)
      src.phi_star = last.phi_star;
    else
      src.stationary_note = "the last TopState has has_stationary_state = false";
    src.phi_star_source = "the last TopState's phi_star (give --scene FILE to solve for it)";
  }
}

struct Outputs {
  std::string csv, json, plot;
};

// The first and last sim_time kept (phi_measured's mark is at 80 % between them); throws BadInput when none is.
std::pair<double, double> kept_span(rosbag::Bag& bag, const Top& top, const Arguments& args) {
  std::uint64_t n = 0;
  double first = 0.0, last = 0.0;
  for_each_state(bag, top, args, [&](const top_sim::Snapshot& s) {
    if (n++ == 0) first = s.t;
    last = s.t;
  });
  if (n == 0)
    throw BadInput{"topic " + top.topic + ": no TopState with sim_time in [" + top_sim::format_number(args.from) +
                   ", " + top_sim::format_number(args.to) + "] s"};
  return {first, last};
}

// The CSV the plot reads: --csv's, else one in a temporary directory (removed by the caller); "" when none.
std::string plot_data(const Outputs& out, std::string& temp_dir) {
  if (out.plot.empty() || !out.csv.empty()) return out.csv;
  char dir_template[] = "/tmp/top_sim_bag_XXXXXX";
  const char* dir = mkdtemp(dir_template);
  if (!dir) return "";
  temp_dir = dir;
  return temp_dir + "/data.csv";
}

// Draws --plot from `data`; false (after the message) when it could not.
bool draw(const std::string& data, const Top& top, const top_sim::RecordedSource& src, const std::string& png) {
  if (data.empty()) {
    std::cerr << kTool << ": --plot = '" << png << "': cannot create a temporary directory for its data\n";
    return false;
  }
  std::vector<std::string> words = {data, png, "--title=" + top.name + " (" + top.topic + ")"};
  if (src.phi_star) words.push_back("--phi-star=" + top_sim::format_number(*src.phi_star));
  return top_sim_cli::run_plot(kTool, "trajectory.py", words, png);
}

// The one-line result of a top.
void report(std::ostream& os, const Top& top, const top_sim::SampledSummary& s, const top_sim::RecordedSource& src) {
  os << top.name << " (" << top.topic << "): " << s.samples << " states, t = " << s.t_first << " to " << s.t_last
     << " s (" << src.skipped << " repeated instants skipped), regime " << top_sim::to_string(s.last.regime);
  if (s.phi_measured) os << ", phi_measured " << *s.phi_measured;
  if (src.phi_star) os << ", phi_star " << *src.phi_star;
  os << ", energy residual " << s.max_energy_residual << "\n";
  if (!src.stationary_note.empty()) os << "  stationary state: " << src.stationary_note << "\n";
}

// One top's CSV, summary and plot; false when an output was not written (after the message).
bool summarise(rosbag::Bag& bag, const Top& top, const Arguments& args, const top_sim::Scene* scene,
               const Outputs& out, std::ostream& log) {
  const auto [t_first, t_last] = kept_span(bag, top, args);
  std::string temp_dir;
  const std::string data = plot_data(out, temp_dir);
  std::ofstream csv;
  bool ok = true;
  if (!data.empty()) {
    csv.open(data);
    if (!csv) std::cerr << kTool << ": --csv = '" << data << "': cannot open for writing\n";
    ok = csv.is_open();
  }
  top_sim::CsvWriter rows(csv);
  if (csv.is_open()) rows.header();
  top_sim::SummaryAccumulator acc(top_sim::mark_time(t_first, t_last));
  top_sim::RecordedSource src;
  src.bag = args.bag;
  src.topic = top.topic;
  src.top = top.name;
  src.scene = scene;
  src.skipped = for_each_state(bag, top, args, [&](const top_sim::Snapshot& s) {
    acc.add(s);
    if (csv.is_open()) rows.row(s);
  });
  const top_sim::SampledSummary s = acc.result();
  set_phi_star(scene, s.last, src);
  if (csv.is_open()) {
    rows.flush();
    csv.close();
    if (!csv) std::cerr << kTool << ": --csv = '" << data << "': writing failed (disk full?)\n";
    ok = static_cast<bool>(csv);
  }
  ok = ok && (out.plot.empty() || draw(data, top, src, out.plot));
  if (!temp_dir.empty()) std::filesystem::remove_all(temp_dir);
  ok = top_sim::write_text_file(kTool, "--json", out.json, top_sim::summary_json(src, s)) && ok;
  report(log, top, s, src);
  return ok;
}

// The scene of --scene, its warnings on stderr; throws BadInput when it is bad.
top_sim::Scene load(const std::string& path) {
  try {
    top_sim::Scene scene = top_sim::load_scene(path);
    for (const auto& w : scene.warnings) std::cerr << kTool << ": warning: " << w << "\n";
    return scene;
  } catch (const std::exception& e) {  // SceneError names file, key, value and range
    throw BadInput{std::string("--scene: bad scene: ") + e.what()};
  }
}

// Every selected top; the exit status.
int run(const Arguments& args) {
  if (!std::filesystem::is_regular_file(args.bag)) throw BadInput{"bag = '" + args.bag + "': no such file"};
  rosbag::Bag bag;
  bag.open(args.bag, rosbag::bagmode::Read);
  std::optional<top_sim::Scene> scene;
  if (!args.scene.empty()) scene = load(args.scene);
  std::vector<std::string> arrays;
  const std::vector<Top> listed = tops_in(bag, arrays);
  const std::vector<Top> tops = select(bag, listed, arrays, args.top);
  const bool several = tops.size() > 1;
  if (several && args.json == "-")
    throw BadInput{"--json = '-': standard output takes one top; the bag has " + std::to_string(tops.size()) +
                   " (choose one with --top, or give a file name)"};
  std::ostream& log = args.json == "-" ? std::cerr : std::cout;
  bool ok = true;
  for (const Top& top : tops) {
    const Outputs out{output_path(args.csv, top, several), output_path(args.json, top, several),
                      output_path(args.plot, top, several)};
    ok = summarise(bag, top, args, scene ? &*scene : nullptr, out, log) && ok;
  }
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (const auto done = top_sim_cli::parse_command_line(kTool, kUsage, parse_arguments, argc, argv, args)) return *done;
  try {
    return run(args);
  } catch (const BadInput& e) {
    std::cerr << kTool << ": " << e.message << "\n";
  } catch (const rosbag::BagException& e) {  // unreadable, truncated or not a bag
    std::cerr << kTool << ": bag = '" << args.bag << "': " << e.what() << "\n";
  }
  return 2;
}
