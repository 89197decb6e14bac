// top_sim_node: a thin ROS adapter over top_sim::Simulator for one or many tops (docs/ros.md, docs/interfaces.md).
// Single-threaded: one loop on the main thread answers the callbacks (subscribers, services, dynamic_reconfigure),
// advances every top within one wall-clock budget per tick and publishes, once per publish period. The parts:
// node_parameters (parameters and scenes), top_input (commands), node_top / top_set (the tops and the sharing of
// the budget), state_output (publishing), node_diagnostics, node_reconfigure.
#include <ros/ros.h>

#include <malloc.h>

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <set>
#include <stdexcept>
#include <memory>
#include <sstream>

#include <diagnostic_updater/diagnostic_updater.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "cpu_affinity.hpp"
#include "node_diagnostics.hpp"
#include "node_parameters.hpp"
#include "node_reconfigure.hpp"
#include "param_yaml.hpp"
#include <ros/package.h>

#include "state_output.hpp"
#include "top_mesh.hpp"
#include "top_input.hpp"
#include "top_set.hpp"
#include "topic_opener.hpp"
#include "top_sim/Kill.h"
#include "top_sim/cpu_time.hpp"
#include "top_sim/ListTops.h"
#include "top_sim/Spawn.h"

namespace {

using top_sim_ros::NodeTop;

constexpr const char* kLaunchTopName = "top";

class TopSimNode {
 public:
  TopSimNode() : pnh_("~") {}

  // Reads parameters and scenes; false (after a fatal log) when anything is bad.
  bool init() {
    std::vector<std::pair<std::string, top_sim::Scene>> start_tops;
    if (!read_start(start_tops)) return false;
    for (const auto& w : scene_.warnings) ROS_WARN("top_sim_node: %s", w.c_str());
    // Stamps: simulated time offset by the clock at start, so rviz at real_time_factor 1 sees current stamps.
    double origin = ros::Time::now().toSec();
    if (origin <= 0.0) origin = ros::WallTime::now().toSec();
    output_ = std::make_unique<top_sim_ros::StateOutput>(nh_, pnh_, params_, origin);
    opener_ = std::make_unique<top_sim_ros::TopicOpener>([this](NodeTop& t) { return open_topics(t); });
    const double wall = ros::WallTime::now().toSec();
    start_wall_ = wall;
    NodeTop& top = tops_.add(std::make_unique<NodeTop>(kLaunchTopName, true, launch_scene_, params_.frames, 0.0,
                                                       params_.real_time_factor, params_.publish_rate, wall));
    connect(top, Topics::now);
    const bool own = top_sim_ros::own_topics(params_.per_top_topics, 1 + start_tops.size());
    for (auto& [name, scene] : start_tops) {
      // Beyond `topics_at_start` tops, a top's own topics follow on the background thread (docs/ros.md).
      const bool background = params_.topics_at_start >= 0 &&
                              tops_.size() >= static_cast<std::size_t>(std::max(params_.topics_at_start, 1));
      const std::string error = spawn(name, scene, !own ? Topics::none : background ? Topics::later : Topics::now);
      if (!error.empty()) {
        ROS_FATAL("top_sim_node: %s/tops/%s: %s", pnh_.getNamespace().c_str(), name.c_str(), error.c_str());
        return false;
      }
    }
    advertise_services();
    // Commands for any top by name: one subscription, however many tops (docs/ros.md, "Many tops").
    tops_command_ = pnh_.subscribe("tops/command", kTopsCommandQueue, &TopSimNode::on_tops_command, this,
                                   ros::TransportHints().tcpNoDelay());
    diagnostics_ = std::make_unique<top_sim_ros::NodeDiagnostics>(wall);
    updater_.setHardwareID("top_sim");
    updater_.add("simulation", [this](diagnostic_updater::DiagnosticStatusWrapper& st) { diagnose(st); });
    start_reconfigure();
    ROS_INFO("top_sim_node: %s, alpha %.4g rad, spin %.4g rad/s, %s, %zu tops, publishing at %.4g Hz, real-time "
             "factor %.4g", launch_scene_.source.c_str(), launch_scene_.model.plane.inclination,
             launch_scene_.initial.spin, top_sim::to_string(launch_scene_.integrator.method), tops_.size(),
             params_.publish_rate, params_.real_time_factor);
    topics_pending_ = opener_->pending();
    if (topics_pending_ > 0)
      ROS_INFO("top_sim_node: the own topics of %zu of the %zu tops are being advertised in the background "
               "(~topics_at_start = %d); ~top_states, ~list and the services serve every top now",
               topics_pending_, tops_.size(), params_.topics_at_start);
    return true;
  }

  // The publish loop: the callbacks that arrived (answered at once; the tick right after applies and publishes the
  // commands), one tick, then sleep to the next period. The physics of a tick is bounded by half the period shared
  // by all tops, so the loop keeps its rate whatever the scenes cost. (A WallTimer hands every tick from roscpp's
  // timer thread to the spinner: at 1 kHz those context switches cost more CPU than the simulation.)
  void run() {
    ros::WallTime next = ros::WallTime::now();
    while (ros::ok()) {
      ros::spinOnce();
      tick();
      next += ros::WallDuration(1.0 / params_.publish_rate);
      const ros::WallTime now = ros::WallTime::now();
      if (next < now)
        next = now;  // fell behind (CPU starved): do not burst to catch up
      else
        ros::WallTime::sleepUntil(next);
    }
  }

 private:
  // ---- start-up -------------------------------------------------------------------------------------------------
  bool read_start(std::vector<std::pair<std::string, top_sim::Scene>>& start_tops) {
    const std::string ns = pnh_.getNamespace();
    top_sim::Command start;  // dynamic_reconfigure's values found at start, folded into launch_scene_
    try {
      XmlRpc::XmlRpcValue tree;
      ros::param::get(ns, tree);
      top_sim_ros::ParamReader params(tree, ns);
      params_ = top_sim_ros::read_node_parameters(params);
      if (params_.config_dir.empty()) params_.config_dir = ros::package::getPath("top_sim") + "/config";
      if (!params.has("scene_file") && !params.has("scene"))
        ROS_INFO("top_sim_node: no ~scene_file or ~scene: the default scene %s",
                 top_sim_ros::default_scene_file(params_.config_dir).c_str());
      scene_ = top_sim_ros::read_node_scene(params, params_.config_dir);
      // The scene's view hint sets the pace unless ~real_time_factor was given (the launch's argument overrides it).
      if (!params.has("real_time_factor") && scene_.view.real_time_factor > 0.0)
        params_.real_time_factor = scene_.view.real_time_factor;
      start_tops = top_sim_ros::read_start_tops(params, params_.config_dir, scene_);
      for (const std::string& key : top_sim_ros::reconfigure_physics_keys()) params.know(key);
      params.know("view");  // written by the node itself (publish_view): a restart without clear_params finds it
      start = top_sim_ros::start_command(params.tree(), scene_.model, ns);
      params.check_unknown();
    } catch (const top_sim::SceneError& e) {
      ROS_FATAL("top_sim_node: bad scene: %s", e.what());
      return false;
    } catch (const std::exception& e) {
      ROS_FATAL("top_sim_node: bad parameter: %s", e.what());
      return false;
    }
    const std::string error = top_sim::validate(start, scene_.model);
    if (!error.empty()) {
      ROS_FATAL("top_sim_node: bad dynamic_reconfigure parameter under %s at start: %s", ns.c_str(), error.c_str());
      return false;
    }
    try {
      launch_scene_ = top_sim_ros::start_scene(scene_, start);
    } catch (const std::exception& e) {
      ROS_FATAL("top_sim_node: bad dynamic_reconfigure parameter under %s at start: %s", ns.c_str(), e.what());
      return false;
    }
    if (!start.empty())
      ROS_INFO("top_sim_node: dynamic_reconfigure values found under %s are the launch-time top's start (and "
               "~reset's)", ns.c_str());
    publish_view();
    return true;
  }

  // The scene's view hint as ~view/camera and ~view/distance, for the rviz panel to turn the camera to, and the
  // body's reach from its contact point, ~view/reach, for top_sim_interactive to rest its controls beside it.
  void publish_view() {
    pnh_.setParam("view/camera", std::string(top_sim::to_string(scene_.view.camera)));
    pnh_.setParam("view/distance", scene_.view.distance);
    pnh_.setParam("view/reach", top_sim_ros::reach_from_contact(scene_.model.top, scene_.model.shapes));
  }

  // A top's own topics: now, later (on the opener's thread; installed into the top on the loop's thread) or none
  // (~per_top_topics false: the top is on ~top_states and ~tops/command only).
  enum class Topics { now, later, none };
  void connect(NodeTop& top, Topics topics) {
    output_->open(top);
    if (topics == Topics::later) opener_->add(top);
    if (topics == Topics::now) top.install(open_topics(top));
  }

  // A top's own topics (NodeTop builds them; thread-safe); the launch-time top's accepted commands are shown in
  // dynamic_reconfigure.
  top_sim_ros::TopTopics open_topics(NodeTop& top) {
    top_sim::Simulator& sim = top.sim();
    const bool shown = top.launch_top();
    return top.open_topics(
        pnh_, output_->subscription_changes(),
        [this, &sim, shown](const top_sim::Command& c) {  // runs in spinOnce() on the loop's thread
          const std::string error = sim.submit(c);
          if (error.empty() && shown && reconfigure_) reconfigure_->record_for_push(c);
          return error;
        },
        [this, &top](const top_sim::TopCommand& m) { return command(top, m); }, rejections_);
  }

  // A whole TopCommand on one top (its own ~command or ~tops/command, on the loop's thread); "" or why not. What the
  // launch-time top accepts shows in dynamic_reconfigure, its reset as ~reset's does.
  std::string command(NodeTop& top, const top_sim::TopCommand& m) {
    top_sim::Command applied;
    const std::string error = top.command(m, ros::WallTime::now().toSec(), applied);
    if (error.empty() && top.launch_top() && reconfigure_) {
      if (m.reset) reconfigure_->record_scene_for_push(launch_scene_);
      if (!applied.empty()) reconfigure_->record_for_push(applied);
    }
    return error;
  }

  // ~tops/command: the top its `name` names; an empty or unknown name, or a bad field, is a throttled warning and
  // nothing is applied.
  void on_tops_command(const top_sim::TopCommand::ConstPtr& m) {
    std::string error;
    NodeTop* top = m->name.empty() ? nullptr : tops_.find(m->name);
    if (m->name.empty())
      error = "name is empty: give the top's name (~list gives the names of the " + tops_count(tops_.size()) + ")";
    else if (!top)
      error = "name = '" + m->name + "': no top of that name (~list gives the names of the " +
              tops_count(tops_.size()) + ")";
    else if (std::string why = command(*top, *m); !why.empty())
      error = "top '" + m->name + "': " + why;
    if (!error.empty()) rejections_.warn("tops/command rejected: " + error, ros::WallTime::now().toSec());
  }

  void advertise_services() {
    reset_srv_ = pnh_.advertiseService("reset", &TopSimNode::on_reset, this);
    pause_srv_ = pnh_.advertiseService("pause", &TopSimNode::on_pause, this);
    spawn_srv_ = pnh_.advertiseService("spawn", &TopSimNode::on_spawn, this);
    kill_srv_ = pnh_.advertiseService("kill", &TopSimNode::on_kill, this);
    list_srv_ = pnh_.advertiseService("list", &TopSimNode::on_list, this);
  }

  void start_reconfigure() {
    top_sim_ros::ReconfigureHooks hooks;
    hooks.submit = [this](const top_sim::Command& c) {
      const std::string error = tops_.launch_top().sim().submit(c);
      if (error.empty())
        reconfigure_->record_for_push(c);
      else
        rejections_.warn("dynamic_reconfigure rejected: " + error, ros::WallTime::now().toSec());
      return error;
    };
    hooks.set_real_time_factor = [this](double f) {
      params_.real_time_factor = f;
      const double wall = ros::WallTime::now().toSec();
      for (auto& t : tops_) t->pacer().set_real_time_factor(f, wall, t->sim().time());
    };
    hooks.set_publish_rate = [this](double rate) {
      params_.publish_rate = rate;  // run() reads it every period
      for (auto& t : tops_) t->pacer().set_rate(rate);  // the physics budget is a fraction of the period
    };
    reconfigure_ = std::make_unique<top_sim_ros::NodeReconfigure>(nh_, pnh_, launch_scene_,
                                                                  params_.real_time_factor, params_.publish_rate,
                                                                  std::move(hooks));
  }

  // ---- one period ---------------------------------------------------------------------------------------------
  void tick() {
    const double wall = ros::WallTime::now().toSec();
    install_topics(wall);
    const double cpu0 = top_sim::thread_cpu_seconds();
    std::size_t steps = 0;
    tops_.advance(wall, tops_.launch_top().pacer().budget(), paused_, [&](top_sim_ros::NodeTop& t) {
      steps += t.take_steps();
      t.report(params_.real_time_factor, params_.publish_rate, paused_);
    });
    diagnostics_->add_physics(steps, top_sim::thread_cpu_seconds() - cpu0);
    rejections_.flush(wall);
    output_->publish(tops_, wall, paused_, params_.real_time_factor);
    updater_.update();
  }

  // Tops whose topics the opener has finished get them before this tick publishes.
  void install_topics(double wall) {
    if (topics_pending_ == 0) return;
    opener_->install();
    topics_pending_ = opener_->pending();
    if (topics_pending_ == 0)
      ROS_INFO("top_sim_node: the own topics of all %zu tops are advertised, %.1f s after the node started",
               tops_.size(), wall - start_wall_);
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& st) {
    top_sim_ros::NodeStatus node;
    node.paused = paused_;
    node.requested_factor = params_.real_time_factor;
    node.publish_rate = params_.publish_rate;
    node.published = output_->published();
    node.rejected = rejections_.total();
    node.lcm = output_->lcm_status();
    node.topics_pending = topics_pending_;
    diagnostics_->fill(st, tops_, node, ros::WallTime::now().toSec());
  }

  // ---- services -----------------------------------------------------------------------------------------------
  static std::string tops_count(std::size_t n) { return std::to_string(n) + (n == 1 ? " top" : " tops"); }

  // "" or why not: a new top `name` on `scene`, starting at the node's current simulated time.
  std::string spawn(const std::string& name, const top_sim::Scene& scene, Topics topics) {
    const std::string bad = tops_.check_new_name(name);
    if (!bad.empty()) return bad;
    NodeTop& launch = tops_.launch_top();
    const double node_time = launch.stamp_offset() + launch.sim().time();
    auto top = std::make_unique<NodeTop>(name, false, scene, top_sim_ros::spawned_frames(params_.frames, name),
                                         node_time, params_.real_time_factor, params_.publish_rate,
                                         ros::WallTime::now().toSec());
    connect(tops_.add(std::move(top)), topics);
    for (const auto& w : scene.warnings) ROS_WARN("top_sim_node: top %s: %s", name.c_str(), w.c_str());
    return "";
  }

  using NewTops = std::vector<std::pair<std::string, top_sim::Scene>>;
  static constexpr std::uint32_t kMaxCopies = 100000;

  top_sim::Scene spawn_scene(const std::string& text, const std::string& source) {
    try {
      XmlRpc::XmlRpcValue value(text);
      return top_sim_ros::scene_value(value, source, params_.config_dir, scene_);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("bad scene: ") + e.what());
    }
  }

  // The names a spawn asks for: `name`, `names`, or `copies` of NAME0, NAME1, ...; throws std::invalid_argument.
  static std::vector<std::string> spawn_names(const top_sim::Spawn::Request& req) {
    if (req.copies > 0 && !req.names.empty())
      throw std::invalid_argument("copies = " + std::to_string(req.copies) + " and " +
                                  std::to_string(req.names.size()) + " names: give copies or names, not both");
    if (req.copies > kMaxCopies)
      throw std::invalid_argument("copies = " + std::to_string(req.copies) + ": must be 0 (one top) to " +
                                  std::to_string(kMaxCopies));
    if (!req.names.empty() && !req.name.empty())
      throw std::invalid_argument("name = '" + req.name + "' and a list of names: give one of them");
    std::vector<std::string> names = req.names;
    for (std::uint32_t i = 0; i < req.copies; ++i) names.push_back(req.name + std::to_string(i));
    if (names.empty()) names.push_back(req.name);
    return names;
  }

  // The tops a spawn asks for, every name checked and every scene read before any is made; throws
  // std::invalid_argument naming the first problem.
  NewTops requested_tops(const top_sim::Spawn::Request& req) {
    const std::vector<std::string> names = spawn_names(req);
    if (!req.scenes.empty() && req.scenes.size() != names.size())
      throw std::invalid_argument(std::to_string(req.scenes.size()) + " scenes for " + tops_count(names.size()) +
                                  ": give one scene per name, or none (all on `scene`)");
    std::set<std::string> seen;
    for (const std::string& name : names) {
      const std::string bad = tops_.check_new_name(name);
      if (!bad.empty()) throw std::invalid_argument(bad);
      if (!seen.insert(name).second) throw std::invalid_argument("name '" + name + "' is given twice");
    }
    NewTops tops;
    tops.reserve(names.size());
    if (req.scenes.empty()) {  // read once for all
      const top_sim::Scene scene = spawn_scene(req.scene, "spawn " + names.front());
      for (const std::string& name : names) tops.emplace_back(name, scene);
    } else {
      for (std::size_t i = 0; i < names.size(); ++i)
        tops.emplace_back(names[i], spawn_scene(req.scenes[i], "spawn " + names[i]));
    }
    return tops;
  }

  // Whether `n` new tops get their own topics: as asked, or by ~per_top_topics counting them.
  Topics spawn_topics(std::uint8_t asked, std::size_t n) const {
    using Req = top_sim::Spawn::Request;
    if (asked == Req::PER_TOP_TOPICS_ON) return Topics::now;
    if (asked == Req::PER_TOP_TOPICS_OFF) return Topics::none;
    if (asked != Req::PER_TOP_TOPICS_DEFAULT)
      throw std::invalid_argument("per_top_topics = " + std::to_string(asked) +
                                  ": must be 0 (the node's ~per_top_topics rule), 1 (own topics) or 2 (none)");
    return top_sim_ros::own_topics(params_.per_top_topics, tops_.size() + n) ? Topics::now : Topics::none;
  }

  bool on_spawn(top_sim::Spawn::Request& req, top_sim::Spawn::Response& res) {
    const double t0 = ros::WallTime::now().toSec();
    try {
      const NewTops tops = requested_tops(req);
      const Topics topics = spawn_topics(req.per_top_topics, tops.size());
      for (const auto& [name, scene] : tops) {
        res.message = spawn(name, scene, topics);  // checked above: fails only on a roscpp error
        if (!res.message.empty()) break;
        res.names.push_back(name);
      }
      if (res.message.empty()) res.message = spawned_sentence(res.names, topics, t0);
      res.success = res.names.size() == tops.size();
    } catch (const std::exception& e) {
      res.message = e.what();
    }
    if (res.success)
      ROS_INFO("top_sim_node: %s", res.message.c_str());
    else
      ROS_WARN("top_sim_node: spawn '%s' refused: %s",
               req.name.empty() && !req.names.empty() ? req.names.front().c_str() : req.name.c_str(),
               res.message.c_str());
    return true;
  }

  std::string spawned_sentence(const std::vector<std::string>& names, Topics topics, double t0) const {
    if (names.size() == 1 && topics == Topics::now)
      return "spawned top '" + names.front() + "' (" + tops_count(tops_.size()) + " now)";
    std::ostringstream os;
    os << "spawned " << (names.size() == 1 ? "top '" + names.front() + "'"
                                           : tops_count(names.size()) + " '" + names.front() + "' to '" +
                                                 names.back() + "'")
       << " (" << tops_count(tops_.size()) << " now; "
       << (topics == Topics::none ? "no own topics: ~top_states and ~tops/command" : "with their own topics")
       << ") in " << std::setprecision(3) << ros::WallTime::now().toSec() - t0 << " s";
    return os.str();
  }

  bool on_kill(top_sim::Kill::Request& req, top_sim::Kill::Response& res) {
    res.success = false;
    if (req.name == kLaunchTopName) {
      res.message = std::string("'") + kLaunchTopName + "' is the launch-time top (it carries ~top_state, the plane "
                    "and dynamic_reconfigure): it cannot be killed; kill the spawned tops, or ~pause the node";
    } else if (std::unique_ptr<NodeTop> top = tops_.remove(req.name)) {
      opener_->forget(*top);  // its topics may still be on their way
      topics_pending_ = opener_->pending();
      output_->close(*top);
      res.success = true;
      res.message = "killed top '" + req.name + "' (" + tops_count(tops_.size()) + " left)";
    } else {
      res.message = "no top named '" + req.name + "' (~list gives the names)";
    }
    if (res.success)
      ROS_INFO("top_sim_node: %s", res.message.c_str());
    else
      ROS_WARN("top_sim_node: kill refused: %s", res.message.c_str());
    return true;
  }

  bool on_list(top_sim::ListTops::Request&, top_sim::ListTops::Response& res) {
    res.names = tops_.names();
    return true;
  }

  bool on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    const double t = tops_.launch_top().sim().time();
    const double wall = ros::WallTime::now().toSec();
    for (auto& top : tops_) top->reset(wall);
    // The launch-time top returns to the start the user chose (alpha:=, spin:=): its scene holds them.
    reconfigure_->record_scene_for_push(launch_scene_);
    res.success = true;
    std::ostringstream os;
    if (tops_.size() == 1)
      os << "reset top '" << tops_.launch_top().name() << "' to its start";
    else
      os << "reset " << tops_.size() << " tops to their starts";
    os << " at t = " << t << " s; time keeps running forward";
    res.message = os.str();
    ROS_INFO("top_sim_node: %s", res.message.c_str());
    return true;
  }

  bool on_pause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
    if (paused_ != static_cast<bool>(req.data)) {
      paused_ = req.data;
      const double wall = ros::WallTime::now().toSec();
      for (auto& top : tops_) top->reanchor(wall, true);
    }
    res.success = true;
    res.message = paused_ ? "paused" : "running";
    return true;
  }

  ros::NodeHandle nh_, pnh_;
  top_sim_ros::NodeParameters params_;
  top_sim::Scene scene_;  // as read: the base of spawned tops and of ~tops
  top_sim::Scene launch_scene_;  // scene_ with dynamic_reconfigure's values found at start (alpha:=, spin:=, ...)
  top_sim_ros::TopSet tops_;
  top_sim_ros::RejectionLog rejections_;
  std::unique_ptr<top_sim_ros::StateOutput> output_;
  std::unique_ptr<top_sim_ros::NodeDiagnostics> diagnostics_;
  std::unique_ptr<top_sim_ros::NodeReconfigure> reconfigure_;
  diagnostic_updater::Updater updater_;
  ros::ServiceServer reset_srv_, pause_srv_, spawn_srv_, kill_srv_, list_srv_;
  ros::Subscriber tops_command_;
  static constexpr uint32_t kTopsCommandQueue = 10000;  // one command for each of 10,000 tops in a burst
  bool paused_ = false;
  double start_wall_ = 0.0;
  std::size_t topics_pending_ = 0;  // tops whose own topics the opener has not handed over yet
  // Last, so destroyed first: its thread stops before the tops and handles it uses go.
  std::unique_ptr<top_sim_ros::TopicOpener> opener_;
};

// ~cpu_affinity, applied before roscpp starts its threads (at the first NodeHandle) so that they all inherit it;
// false (after a fatal log) when it is bad or cannot be applied.
bool pin_from_parameter() {
  const std::string ns = ros::this_node::getName();  // the private namespace
  try {
    XmlRpc::XmlRpcValue tree;
    ros::param::get(ns, tree);
    top_sim_ros::ParamReader params(tree, ns);
    const int cpu = top_sim_ros::read_cpu_affinity(params);
    if (cpu == top_sim_ros::kNoCpuAffinity) return true;
    const std::string error = top_sim_ros::pin_process_to_cpu(cpu);
    if (!error.empty()) {
      ROS_FATAL("top_sim_node: %s/cpu_affinity = %d: %s", ns.c_str(), cpu, error.c_str());
      return false;
    }
    ROS_INFO("top_sim_node: all threads on CPU %d (~cpu_affinity)", cpu);
  } catch (const std::exception& e) {
    ROS_FATAL("top_sim_node: bad parameter: %s", e.what());
    return false;
  }
  return true;
}

// Pinned, the loop shares its CPU with roscpp's threads: they become SCHED_BATCH, so a publish no longer switches to
// the I/O thread at once (which then walks all publications once per message); it sends the tick's messages together.
void yield_when_pinned() {
  if (top_sim_ros::allowed_cpus().find_first_of(",-") != std::string::npos) return;  // not on one CPU
  const std::string error = top_sim_ros::yield_other_threads();
  if (!error.empty()) ROS_WARN("top_sim_node: %s (roscpp's threads keep their priority)", error.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  // roscpp serialises each top_states array (about 0.5 kB per top) into a new buffer: taken from the heap and kept
  // there, instead of mapped and page-faulted in afresh every tick (perf: 2 % of the node at 1000 tops).
  mallopt(M_MMAP_THRESHOLD, 16 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  ros::init(argc, argv, "top_sim_node");
  if (!pin_from_parameter()) return 2;
  TopSimNode node;  // roscpp's threads start here
  if (!node.init()) return 2;
  yield_when_pinned();
  node.run();
  return 0;
}
