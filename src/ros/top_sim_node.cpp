// top_sim_node: a thin ROS adapter over top_sim::Simulator (docs/ros.md, docs/interfaces.md).
// Single-threaded: one loop on the main thread answers the callbacks (subscribers, services, dynamic_reconfigure),
// advances the core within a wall-clock budget (top_sim::Pacer) and publishes, once per publish period.
#include <ros/ros.h>

#include <cmath>
#include <ctime>
#include <memory>
#include <set>
#include <sstream>

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nav_msgs/Path.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Float64.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.hpp"
#include "param_yaml.hpp"
#include "top_sim/TopCommand.h"
#include "top_sim/TopSimConfig.h"
#include "top_sim/TopState.h"
#include "top_sim/pacing.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#ifdef TOP_SIM_HAVE_LCM
#include "lcm_publisher.hpp"
#endif

namespace {

// The node's own parameters (publish_rate and real_time_factor are dynamic_reconfigure's too). Everything else
// under ~ is either a physics key of dynamic_reconfigure (top_sim_ros::reconfigure_physics_keys) or the scene.
std::set<std::string> node_keys() {
  return {"publish_rate", "real_time_factor", "publish_clock", "world_frame", "plane_frame", "top_frame",
          "path_length",  "lcm_url",          "lcm_channel",   "marker_rate", "path_rate",  "path_resolution",
          "config_dir",   "scene_file"};
}
const std::set<std::string> kNodeKeys = node_keys();

std::set<std::string> union_of(const std::set<std::string>& a, const std::set<std::string>& b) {
  std::set<std::string> u = a;
  u.insert(b.begin(), b.end());
  return u;
}

constexpr double kMaxPublishRate = 10000.0;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

std::string rate_error(const char* name, double v, const char* range) {
  std::ostringstream os;
  os << name << " = " << v << ": must be " << range;
  return os.str();
}

class TopSimNode {
 public:
  TopSimNode() : pnh_("~") {}

  // Reads parameters and the scene; false (after a fatal log) when the scene is bad.
  bool init() {
    std::string lcm_url, lcm_channel, config_dir, scene_file;
    if (!read_parameters(lcm_url, lcm_channel, config_dir, scene_file) || !read_scene(config_dir, scene_file))
      return false;
    for (const auto& w : scene_.warnings) ROS_WARN("top_sim_node: %s", w.c_str());
    sim_ = std::make_unique<top_sim::Simulator>(scene_);
    if (!start_command_.empty()) {
      sim_->submit(start_command_);  // validated in read_scene()
      ROS_INFO("top_sim_node: dynamic_reconfigure values found under %s applied at t = 0 (reset returns to the "
               "scene's)", pnh_.getNamespace().c_str());
    }
    advertise();
    if (!lcm_url.empty()) open_lcm(lcm_url, lcm_channel);

    updater_.setHardwareID("top_sim");
    updater_.add("simulation", this, &TopSimNode::diagnose);

    // Stamps: simulated time offset by the wall clock at start, so rviz at real_time_factor 1 sees current stamps.
    stamp_origin_ = ros::Time::now().toSec();
    if (stamp_origin_ <= 0.0) stamp_origin_ = ros::WallTime::now().toSec();
    pacer_ = std::make_unique<top_sim::Pacer>(real_time_factor_, publish_rate_, ros::WallTime::now().toSec(),
                                              sim_->time());
    diag_wall_ = ros::WallTime::now().toSec();
    diag_cpu_ = process_cpu_seconds();
    start_reconfigure();
    ROS_INFO("top_sim_node: %s, alpha %.4g rad, spin %.4g rad/s, %s, publishing at %.4g Hz, real-time factor %.4g",
             scene_.source.c_str(), scene_.model.plane.inclination, scene_.initial.spin,
             top_sim::to_string(scene_.integrator.method), publish_rate_, real_time_factor_);
    return true;
  }
  // The publish loop on the main thread: the callbacks that arrived (commands and services, answered at once; the
  // tick right after applies and publishes the commands), one tick, then sleep to the next period. The physics of
  // a tick is bounded by the Pacer's budget (half the period), so the loop keeps its rate whatever the scene costs.
  // (A WallTimer hands every tick from roscpp's timer thread to the spinner: at 1 kHz those context switches cost
  // more CPU than the simulation.)
  void run() {
    ros::WallTime next = ros::WallTime::now();
    while (ros::ok()) {
      ros::spinOnce();
      tick();
      next += ros::WallDuration(1.0 / publish_rate_);
      const ros::WallTime now = ros::WallTime::now();
      if (next < now)
        next = now;  // fell behind (CPU starved): do not burst to catch up
      else
        ros::WallTime::sleepUntil(next);
    }
  }

 private:
  // ---- start-up -------------------------------------------------------------------------------------------------
  // The node's own parameters; false (after a fatal log) when one is out of range.
  bool read_parameters(std::string& lcm_url, std::string& lcm_channel, std::string& config_dir,
                       std::string& scene_file) {
    pnh_.param("publish_rate", publish_rate_, 200.0);
    pnh_.param("real_time_factor", real_time_factor_, 1.0);
    pnh_.param("publish_clock", publish_clock_, false);
    pnh_.param("world_frame", frames_.world, std::string("world"));
    pnh_.param("plane_frame", frames_.plane, std::string("plane"));
    pnh_.param("top_frame", frames_.top, std::string("top"));
    pnh_.param("path_length", path_length_, 2000);
    pnh_.param("path_resolution", path_resolution_, 2.0e-4);
    pnh_.param("marker_rate", marker_rate_, 30.0);
    pnh_.param("path_rate", path_rate_, 10.0);
    pnh_.param("lcm_url", lcm_url, std::string());
    pnh_.param("lcm_channel", lcm_channel, std::string("TOP_STATE"));
    pnh_.param("config_dir", config_dir, std::string());
    pnh_.param("scene_file", scene_file, std::string());

    std::string bad;
    if (!(std::isfinite(publish_rate_) && publish_rate_ > 0.0 && publish_rate_ <= kMaxPublishRate))
      bad = rate_error("publish_rate", publish_rate_, "in (0, 10000] Hz");
    else if (!(std::isfinite(real_time_factor_) && real_time_factor_ >= 0.0))
      bad = rate_error("real_time_factor", real_time_factor_, ">= 0 and finite (0 = as fast as possible)");
    else if (path_length_ < 1)
      bad = rate_error("path_length", path_length_, ">= 1 (poses kept)");
    else if (!(std::isfinite(marker_rate_) && marker_rate_ > 0.0))
      bad = rate_error("marker_rate", marker_rate_, "> 0 Hz");
    else if (!(std::isfinite(path_rate_) && path_rate_ > 0.0))
      bad = rate_error("path_rate", path_rate_, "> 0 Hz");
    else if (!(std::isfinite(path_resolution_) && path_resolution_ >= 0.0))
      bad = rate_error("path_resolution", path_resolution_, ">= 0 m");
    if (!bad.empty()) {
      ROS_FATAL("top_sim_node: parameter %s/%s", pnh_.getNamespace().c_str(), bad.c_str());
      return false;
    }
    return true;
  }

  // The scene: from `scene_file` through the core's loader, exactly as top_sim_run reads it (duplicate keys, number
  // syntax and all), or else from the private parameters other than the node's. dynamic_reconfigure's physics keys
  // found at start become a command applied at t = 0. False (after a fatal log) when anything is bad.
  bool read_scene(const std::string& config_dir, const std::string& scene_file) {
    const std::string ns = pnh_.getNamespace();
    try {
      XmlRpc::XmlRpcValue tree;
      ros::param::get(ns, tree);
      const std::set<std::string> not_scene = union_of(kNodeKeys, top_sim_ros::reconfigure_physics_keys());
      const YAML::Node yaml = top_sim_ros::scene_yaml(tree, not_scene, ns);
      if (scene_file.empty()) {
        scene_ = top_sim::parse_scene(yaml, ns, config_dir);
      } else if (yaml.size() > 0) {
        ROS_FATAL("top_sim_node: the scene comes from one place: %s/scene_file = '%s' and scene parameters under %s "
                  "(%s); put them in the file, or drop scene_file", ns.c_str(), scene_file.c_str(), ns.c_str(),
                  key_list(yaml).c_str());
        return false;
      } else {
        scene_ = top_sim::load_scene(scene_file);
      }
      start_command_ = top_sim_ros::start_command(tree, scene_.model, ns);
    } catch (const top_sim::SceneError& e) {
      ROS_FATAL("top_sim_node: bad scene: %s", e.what());
      return false;
    } catch (const std::exception& e) {
      ROS_FATAL("top_sim_node: bad parameter: %s", e.what());
      return false;
    }
    const std::string error = top_sim::validate(start_command_, scene_.model);
    if (!error.empty()) {
      ROS_FATAL("top_sim_node: bad dynamic_reconfigure parameter under %s at start: %s", ns.c_str(), error.c_str());
      return false;
    }
    return true;
  }

  static std::string key_list(const YAML::Node& map) {
    std::string out;
    for (const auto& kv : map) out += (out.empty() ? "" : ", ") + kv.first.as<std::string>();
    return out;
  }

  void advertise() {
    state_pub_ = pnh_.advertise<top_sim::TopState>("top_state", 10);
    marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 2);
    path_pub_ = pnh_.advertise<nav_msgs::Path>("path", 2);
    if (publish_clock_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    // No Nagle delay on commands: their latency is part of the contract (two publish periods).
    const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    // Queues of kCommandQueue: a 1 kHz command stream is 5 per 200 Hz tick; 10 dropped 0.24 % of a flood on a busy CPU.
    inclination_sub_ = pnh_.subscribe("inclination", kCommandQueue, &TopSimNode::on_inclination, this, hints);
    spin_sub_ = pnh_.subscribe("spin", kCommandQueue, &TopSimNode::on_spin, this, hints);
    command_sub_ = pnh_.subscribe("command", kCommandQueue, &TopSimNode::on_command, this, hints);
    reset_srv_ = pnh_.advertiseService("reset", &TopSimNode::on_reset, this);
    pause_srv_ = pnh_.advertiseService("pause", &TopSimNode::on_pause, this);
  }

  // LCM is optional: a failure is logged and the node publishes on ROS only.
  void open_lcm(const std::string& lcm_url, const std::string& lcm_channel) {
#ifdef TOP_SIM_HAVE_LCM
    lcm_ = std::make_unique<top_sim_lcm::Publisher>(lcm_url, lcm_channel);
    if (!lcm_->ok()) {
      lcm_status_ = "error: " + lcm_->error();
      ROS_ERROR("top_sim_node: lcm_url = '%s': %s; LCM is off, ROS publishing continues", lcm_url.c_str(),
                lcm_->error().c_str());
      lcm_.reset();
    } else {
      lcm_status_ = "on: " + lcm_url + ", channel " + lcm_channel;
      ROS_INFO("top_sim_node: LCM on '%s', channel %s", lcm_url.c_str(), lcm_channel.c_str());
    }
#else
    (void)lcm_channel;
    lcm_status_ = "error: this build has no LCM support";
    ROS_ERROR("top_sim_node: lcm_url = '%s': this build has no LCM support; ROS publishing continues",
              lcm_url.c_str());
#endif
  }

  void start_reconfigure() {
    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<top_sim::TopSimConfig>>(reconfigure_mutex_, pnh_);
    // The values in force: the scene's, or dynamic_reconfigure's found at start.
    const top_sim::Command& c = start_command_;
    config_.alpha = c.inclination ? *c.inclination : scene_.model.plane.inclination;
    config_.spin = c.spin ? *c.spin : scene_.initial.spin;
    config_.real_time_factor = real_time_factor_;
    config_.publish_rate = publish_rate_;
    friction_to_config(c.friction ? *c.friction : scene_.model.friction, config_);
    reconfigure_->updateConfig(config_);
    reconfigure_->setCallback([this](top_sim::TopSimConfig& cfg, uint32_t level) { on_reconfigure(cfg, level); });

    // updateConfig() sets each parameter on the master (milliseconds): never on a command's path.
    reconfigure_timer_ = nh_.createWallTimer(ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) {
      if (!config_dirty_) return;
      config_dirty_ = false;
      reconfigure_->updateConfig(config_);
    });
  }

  // ---- pacing (top_sim::Pacer, include/top_sim/pacing.hpp) -------------------------------------------------
  void tick() {
    const double wall = ros::WallTime::now().toSec();
    const double cpu0 = thread_cpu_seconds();
    const std::size_t steps0 = sim_->stats().steps;
    const bool running = !paused_ && sim_->fault() == top_sim::ContactFault::none;
    if (!running) {
      sim_->advance_to(sim_->time());  // applies pending commands without moving time
    } else {
      const top_sim::Pacer::Tick t = pacer_->plan(wall, sim_->time());
      sim_->advance_to(t.target, t.budget);  // returns within about the budget, at t.target or short of it
    }
    step_cpu_ += thread_cpu_seconds() - cpu0;
    steps_ += sim_->stats().steps - steps0;
    mode_switches_ += sim_->take_mode_switches().size();  // drained: the core would hold up to 100000 until reset
    report_fault();
    pacer_->record(wall, sim_->time(), running);
    report_pacing();
    flush_rejections(wall);
    publish(wall);
    updater_.update();
  }

  // One log line per change of the Pacer's behind state (the diagnostics say it continuously).
  void report_pacing() {
    if (pacer_->behind() == reported_behind_) return;
    reported_behind_ = pacer_->behind();
    if (reported_behind_)
      ROS_WARN("top_sim_node: %s (the physics gets %.3g ms of each %.3g ms period; debt beyond %.2g s is dropped)",
               behind_text().c_str(), 1e3 * pacer_->budget(), 1e3 / publish_rate_, pacer_->options().max_debt);
    else if (paused_ || sim_->fault() != top_sim::ContactFault::none)
      ROS_INFO("top_sim_node: %s: no longer falling behind", paused_ ? "paused" : "stopped by a contact fault");
    else
      ROS_INFO("top_sim_node: caught up: achieved real-time factor %.4g of requested %.4g",
               pacer_->achieved_factor(), real_time_factor_);
  }

  std::string behind_text() const {
    std::ostringstream os;
    os.precision(3);
    os << "falling behind: achieved " << pacer_->achieved_factor() << " of requested " << real_time_factor_;
    return os.str();
  }

  void report_fault() {
    if (sim_->fault() != top_sim::ContactFault::none && !fault_reported_) {
      ROS_ERROR("top_sim_node: contact fault, simulation stopped (call ~reset): %s", sim_->fault_message().c_str());
      fault_reported_ = true;
    }
  }

  // ---- output -------------------------------------------------------------------------------------------------
  void publish(double wall) {
    const top_sim::Snapshot s = sim_->snapshot();
    if (!top_sim::all_finite(s)) {
      ROS_ERROR_THROTTLE(1.0, "top_sim_node: non-finite state at t = %g s: not published (call ~reset)", s.t);
      return;
    }
    const ros::Time stamp(stamp_origin_ + s.t);
    top_sim::TopState msg;
    top_sim_ros::to_msg(s, stamp, frames_.plane, msg);
    msg.real_time_factor = pacer_->achieved_factor();
    msg.requested_real_time_factor = real_time_factor_;
    msg.paused = paused_;
    state_pub_.publish(msg);

    // tf only when time moved (a repeated stamp is dropped by listeners as TF_REPEATED_DATA).
    if (stamp > last_tf_stamp_) {
      geometry_msgs::TransformStamped wp, pt;
      top_sim_ros::to_transforms(s, stamp, frames_, wp, pt);
      tf_.sendTransform(std::vector<geometry_msgs::TransformStamped>{wp, pt});
      last_tf_stamp_ = stamp;
      if (publish_clock_) {
        rosgraph_msgs::Clock c;
        c.clock = stamp;
        clock_pub_.publish(c);
      }
    }
#ifdef TOP_SIM_HAVE_LCM
    if (lcm_ && !lcm_->publish(s, pacer_->achieved_factor()) && !lcm_send_failed_) {
      ROS_ERROR("top_sim_node: LCM publish on %s failed (reported once)", lcm_->channel().c_str());
      lcm_send_failed_ = true;
    }
#endif
    update_path(s, stamp);
    if (wall - last_marker_wall_ >= 1.0 / marker_rate_ && marker_pub_.getNumSubscribers() > 0) {
      visualization_msgs::MarkerArray markers;
      top_sim_ros::to_markers(s, sim_->model().top, stamp, frames_, markers);
      marker_pub_.publish(markers);
      last_marker_wall_ = wall;
    }
    if (wall - last_path_wall_ >= 1.0 / path_rate_ && path_pub_.getNumSubscribers() > 0) {
      path_.header.stamp = stamp;
      path_.header.frame_id = frames_.plane;
      path_pub_.publish(path_);
      last_path_wall_ = wall;
    }
    ++published_;
  }

  // Contact-point trail: a pose each time the point has moved path_resolution, at most path_length kept.
  void update_path(const top_sim::Snapshot& s, const ros::Time& stamp) {
    const Eigen::Vector3d p = s.contact_point;
    if (!path_.poses.empty()) {
      const auto& q = path_.poses.back().pose.position;
      if ((p - Eigen::Vector3d(q.x, q.y, q.z)).norm() < path_resolution_ && path_resolution_ > 0.0) return;
    }
    geometry_msgs::PoseStamped ps;
    ps.header.stamp = stamp;
    ps.header.frame_id = frames_.plane;
    ps.pose.position.x = p.x();
    ps.pose.position.y = p.y();
    ps.pose.position.z = p.z();
    ps.pose.orientation.w = 1.0;
    path_.poses.push_back(ps);
    if (static_cast<int>(path_.poses.size()) > path_length_)
      path_.poses.erase(path_.poses.begin(), path_.poses.begin() + (path_.poses.size() - path_length_));
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& st) {
    const double wall = ros::WallTime::now().toSec();
    const double cpu = process_cpu_seconds();
    const double dw = wall - diag_wall_;
    const top_sim::Snapshot s = sim_->snapshot();
    const double cpu_share = dw > 0.0 ? (cpu - diag_cpu_) / dw : 0.0;
    const double cost_per_step = steps_ > 0 ? step_cpu_ / steps_ : 0.0;
    const double publish_hz = dw > 0.0 ? (published_ - diag_published_) / dw : 0.0;
    if (sim_->fault() != top_sim::ContactFault::none)
      st.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "contact fault: " + sim_->fault_message());
    else if (pacer_->behind())
      st.summary(diagnostic_msgs::DiagnosticStatus::WARN, behind_text());
    else if (lcm_status_.rfind("error", 0) == 0)
      st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "LCM off: " + lcm_status_);
    else
      st.summary(diagnostic_msgs::DiagnosticStatus::OK, paused_ ? "paused" : "running");
    st.add("simulated time [s]", s.t);
    st.add("requested real-time factor", real_time_factor_);
    st.add("achieved real-time factor", pacer_->achieved_factor());
    st.add("behind", pacer_->behind());
    st.add("physics budget per tick [ms]", 1e3 * pacer_->budget());
    st.add("debt drops (more than 0.5 s behind)", pacer_->debt_drops());
    st.add("dropped simulated time [s]", pacer_->dropped_sim_seconds());
    st.add("rejected commands", rejected_total_);
    st.add("publish rate requested [Hz]", publish_rate_);
    st.add("publish rate achieved [Hz]", publish_hz);
    st.add("integrator steps (window)", steps_);
    st.add("cost per step [us]", 1e6 * cost_per_step);
    st.add("node CPU share [fraction of one core]", cpu_share);
    st.add("energy balance residual", s.energy_balance_residual);
    st.add("max energy balance residual", sim_->max_energy_residual());
    st.add("regime", top_sim::to_string(s.regime));
    st.add("contact mode", top_sim::to_string(s.contact_mode));
    st.add("contact-mode switches", mode_switches_);
    st.add("gap [m]", s.gap);
    st.add("alpha [rad]", s.alpha);
    st.add("spin [rad/s]", s.spin);
    st.add("paused", paused_);
    st.add("lcm", lcm_status_);
    diag_wall_ = wall;
    diag_cpu_ = cpu;
    diag_published_ = published_;
    steps_ = 0;
    step_cpu_ = 0.0;
  }

  // ---- input ---------------------------------------------------------------------------------------------------
  // Submits to the core, which validates; a rejected command leaves the state untouched.
  bool submit(const top_sim::Command& c, const char* source) {
    const std::string error = sim_->submit(c);
    if (!error.empty()) {
      warn_rejected(std::string(source) + " rejected: " + error);
      return false;
    }
    // Keep dynamic_reconfigure showing the live values.
    if (c.inclination) config_.alpha = *c.inclination;
    if (c.spin) config_.spin = *c.spin;
    if (c.friction) friction_to_config(*c.friction, config_);
    if (c.inclination || c.spin || c.friction) config_dirty_ = true;  // pushed by a slow timer, off the command path
    return true;
  }

  // Rejected-command warnings, throttled: the first in full, then at most one per wall second, which names the
  // last rejection and counts the ones suppressed since the previous warning (a flood of bad commands must not
  // flood /rosout). A pending count is flushed by the loop once the second is over.
  void warn_rejected(const std::string& text) {
    ++rejected_total_;
    const double wall = ros::WallTime::now().toSec();
    flush_rejections(wall);  // a pending count goes out first (and starts a new second)
    if (wall - last_reject_warn_ >= kRejectWarnPeriod) {
      ROS_WARN("top_sim_node: %s", text.c_str());
      last_reject_warn_ = wall;
      suppressed_rejects_ = 0;
    } else {
      ++suppressed_rejects_;
      last_reject_text_ = text;
    }
  }

  void flush_rejections(double wall) {
    if (suppressed_rejects_ == 0 || wall - last_reject_warn_ < kRejectWarnPeriod) return;
    ROS_WARN("top_sim_node: %zu more commands rejected in the last %.1f s (warnings suppressed); the last: %s",
             suppressed_rejects_, wall - last_reject_warn_, last_reject_text_.c_str());
    last_reject_warn_ = wall;
    suppressed_rejects_ = 0;
  }

  void on_inclination(const std_msgs::Float64::ConstPtr& m) {
    top_sim::Command c;
    c.inclination = m->data;
    submit(c, "inclination");
  }

  void on_spin(const std_msgs::Float64::ConstPtr& m) {
    top_sim::Command c;
    c.spin = m->data;
    submit(c, "spin");
  }

  void on_command(const top_sim::TopCommand::ConstPtr& m) {
    std::string error;
    const top_sim::Command c = top_sim_ros::to_command(*m, error);
    if (!error.empty()) {
      warn_rejected("command rejected: " + error);
      return;
    }
    submit(c, "command");
  }

  bool on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    const double t = sim_->time();
    sim_->reset();
    path_.poses.clear();
    fault_reported_ = false;
    pacer_->reanchor(ros::WallTime::now().toSec(), sim_->time(), false);  // time keeps running: keep the window
    config_.alpha = scene_.model.plane.inclination;
    config_.spin = scene_.initial.spin;
    friction_to_config(scene_.model.friction, config_);
    config_dirty_ = true;
    res.success = true;
    std::ostringstream os;
    os << "reset to the scene's initial state at t = " << t << " s (time keeps running forward)";
    res.message = os.str();
    ROS_INFO("top_sim_node: %s", res.message.c_str());
    return true;
  }

  bool on_pause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
    if (paused_ != static_cast<bool>(req.data)) {
      paused_ = req.data;
      pacer_->reanchor(ros::WallTime::now().toSec(), sim_->time());
    }
    res.success = true;
    res.message = paused_ ? "paused" : "running";
    return true;
  }

  // dynamic_reconfigure's friction fields are named like the core's parameters.
  static void friction_to_config(const top_sim::FrictionLaw& law, top_sim::TopSimConfig& cfg) {
    cfg.friction_law = top_sim::to_string(law.kind);
#define TOP_SIM_COPY_TO_CONFIG(kind, name, range) cfg.name = law.name;
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_COPY_TO_CONFIG)
#undef TOP_SIM_COPY_TO_CONFIG
  }

  static void friction_from_config(const top_sim::TopSimConfig& cfg, top_sim::FrictionLaw& law) {
#define TOP_SIM_COPY_FROM_CONFIG(kind, name, range) law.name = cfg.name;
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_COPY_FROM_CONFIG)
#undef TOP_SIM_COPY_FROM_CONFIG
  }

  void on_reconfigure(top_sim::TopSimConfig& cfg, uint32_t level) {
    if (!reconfigure_ready_) {  // the first call only echoes the values set in init()
      reconfigure_ready_ = true;
      cfg = config_;
      return;
    }
    top_sim::Command c;
    if ((level & 1) && cfg.alpha != config_.alpha) c.inclination = cfg.alpha;
    if ((level & 2) && cfg.spin != config_.spin) c.spin = cfg.spin;
    if (level & 16) {
      top_sim::FrictionLaw law = sim_->model().friction;
      if (!reconfigured_friction(cfg, law)) {
        cfg = config_;
        return;
      }
      c.friction = law;
    }
    if (!c.empty()) {
      if (!submit(c, "dynamic_reconfigure")) {
        const double rtf = cfg.real_time_factor, rate = cfg.publish_rate;
        cfg = config_;  // show the values in force
        cfg.real_time_factor = rtf;
        cfg.publish_rate = rate;
      }
    }
    reconfigure_pacing(cfg, level);
    config_.real_time_factor = real_time_factor_;
    config_.publish_rate = publish_rate_;
    cfg.alpha = config_.alpha;  // applied or reverted above; either way config_ holds the value in force
    cfg.spin = config_.spin;
  }

  // The law dynamic_reconfigure asks for, over the law in force; false (after a warning) when it names no law or
  // switches to a table, whose points it cannot carry.
  bool reconfigured_friction(const top_sim::TopSimConfig& cfg, top_sim::FrictionLaw& law) {
    top_sim::FrictionLawKind kind;
    if (!top_sim::parse_friction_law_kind(cfg.friction_law, kind)) {
      ROS_WARN("top_sim_node: dynamic_reconfigure friction_law = '%s': must be one of %s", cfg.friction_law.c_str(),
               top_sim::friction_law_names(", ").c_str());
      return false;
    }
    if (kind == top_sim::kFrictionPointsLaw && law.kind != kind) {
      ROS_WARN("top_sim_node: dynamic_reconfigure friction_law = 'table': the points come only from the scene "
               "or a TopCommand; kept the %s law", top_sim::to_string(law.kind));
      return false;
    }
    law.kind = kind;
    friction_from_config(cfg, law);
    return true;
  }

  // real_time_factor (level 4) and publish_rate (level 8): applied when valid, else warned; cfg shows what holds.
  void reconfigure_pacing(top_sim::TopSimConfig& cfg, uint32_t level) {
    if (level & 4) {
      if (std::isfinite(cfg.real_time_factor) && cfg.real_time_factor >= 0.0) {
        real_time_factor_ = cfg.real_time_factor;
        pacer_->set_real_time_factor(real_time_factor_, ros::WallTime::now().toSec(), sim_->time());
      } else {
        ROS_WARN("top_sim_node: %s", rate_error("real_time_factor", cfg.real_time_factor, ">= 0").c_str());
      }
      cfg.real_time_factor = real_time_factor_;
    }
    if (level & 8) {
      if (std::isfinite(cfg.publish_rate) && cfg.publish_rate > 0.0 && cfg.publish_rate <= kMaxPublishRate) {
        publish_rate_ = cfg.publish_rate;  // run() reads it every period
        pacer_->set_rate(publish_rate_);     // the physics budget is a fraction of the period
      } else {
        ROS_WARN("top_sim_node: %s", rate_error("publish_rate", cfg.publish_rate, "in (0, 10000] Hz").c_str());
      }
      cfg.publish_rate = publish_rate_;
    }
  }

  ros::NodeHandle nh_, pnh_;
  top_sim::Scene scene_;
  top_sim::Command start_command_;  // dynamic_reconfigure's values found at start
  std::unique_ptr<top_sim::Simulator> sim_;
  top_sim_ros::Frames frames_;
  double publish_rate_ = 200.0, real_time_factor_ = 1.0, marker_rate_ = 30.0, path_rate_ = 10.0;
  double path_resolution_ = 2.0e-4;
  bool publish_clock_ = false;
  int path_length_ = 2000;

  ros::Publisher state_pub_, marker_pub_, path_pub_, clock_pub_;
  ros::Subscriber inclination_sub_, spin_sub_, command_sub_;
  ros::ServiceServer reset_srv_, pause_srv_;
  ros::WallTimer reconfigure_timer_;
  bool config_dirty_ = false;
  tf2_ros::TransformBroadcaster tf_;
  diagnostic_updater::Updater updater_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<top_sim::TopSimConfig>> reconfigure_;
  top_sim::TopSimConfig config_;
  bool reconfigure_ready_ = false;
  std::string lcm_status_ = "off";
#ifdef TOP_SIM_HAVE_LCM
  std::unique_ptr<top_sim_lcm::Publisher> lcm_;
  bool lcm_send_failed_ = false;
#endif

  double stamp_origin_ = 0.0;
  std::unique_ptr<top_sim::Pacer> pacer_;
  bool paused_ = false, fault_reported_ = false, reported_behind_ = false;
  static constexpr double kRejectWarnPeriod = 1.0;  // wall seconds between rejected-command warnings
  static constexpr uint32_t kCommandQueue = 100;      // messages held per command topic between ticks
  std::size_t mode_switches_ = 0;                     // since start
  double last_reject_warn_ = -1e9;
  std::size_t suppressed_rejects_ = 0, rejected_total_ = 0;
  std::string last_reject_text_;
  ros::Time last_tf_stamp_;
  nav_msgs::Path path_;
  double last_marker_wall_ = 0.0, last_path_wall_ = 0.0;
  double diag_wall_ = 0.0, diag_cpu_ = 0.0, step_cpu_ = 0.0;
  std::size_t steps_ = 0, published_ = 0, diag_published_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "top_sim_node");
  TopSimNode node;
  if (!node.init()) return 2;
  node.run();
  return 0;
}
