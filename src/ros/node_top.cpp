#include "node_top.hpp"

#include <utility>

#include <nav_msgs/Path.h>

#include "top_sim/TopState.h"

namespace top_sim_ros {

Frames spawned_frames(const Frames& node_frames, const std::string& name) {
  Frames f;
  f.world = node_frames.world;
  f.plane = name + "/" + node_frames.plane;
  f.top = name + "/" + node_frames.top;
  f.contact = name + "/" + node_frames.contact;
  f.grid = name + "/" + node_frames.grid;
  return f;
}

NodeTop::NodeTop(std::string name, bool launch_top, top_sim::Scene scene, const Frames& frames, double node_time,
                 double real_time_factor, double rate, double wall)
    : name_(std::move(name)),
      prefix_(launch_top ? "" : name_ + "/"),
      sim_(std::make_unique<top_sim::Simulator>(std::move(scene))),
      pacer_(real_time_factor, rate, wall, sim_->time()),
      frames_(frames),
      node_time_(node_time) {
  output.markers.set_shapes(sim_->model().shapes);
}

namespace {
// `changes` counts every subscription change of every top: the per-top mirrors are refreshed only then.
template <class M>
ros::Publisher counted(ros::NodeHandle& pnh, const std::string& topic, uint32_t queue,
                       const std::shared_ptr<int>& count, const std::shared_ptr<unsigned>& changes) {
  return pnh.advertise<M>(
      topic, queue, [count, changes](const ros::SingleSubscriberPublisher&) { ++*count; ++*changes; },
      [count, changes](const ros::SingleSubscriberPublisher&) { --*count; ++*changes; });
}
}  // namespace

// The publishers' callbacks run in spinOnce() on the loop's thread, whichever thread advertised.
TopTopics NodeTop::open_topics(ros::NodeHandle& pnh, const std::shared_ptr<unsigned>& changes, SubmitCommand submit,
                               ApplyMessage apply, RejectionLog& log) const {
  TopTopics t;
  t.state = counted<top_sim::TopState>(pnh, prefix_ + "top_state", 10, output.state_subscribers, changes);
  t.path = counted<nav_msgs::Path>(pnh, prefix_ + "path", 2, output.path_subscribers, changes);
  t.input = std::make_unique<TopInput>(pnh, prefix_, name_, std::move(submit), std::move(apply), log);
  return t;
}

void NodeTop::install(TopTopics topics) {
  output.state = std::move(topics.state);
  output.path = std::move(topics.path);
  input_ = std::move(topics.input);
}

void NodeTop::advance(double wall, double budget, bool paused, std::chrono::steady_clock::time_point start) {
  const bool running = !paused && !paused_ && !sim_->stopped();
  if (!running) {
    sim_->advance_to(sim_->time());  // applies pending commands without moving time
  } else {
    const top_sim::Pacer::Tick t = pacer_.plan(wall, sim_->time());
    sim_->advance_to(t.target, budget, start);  // returns within about the budget, at t.target or short of it
  }
  mode_switches_ += sim_->take_mode_switches().size();  // drained: the core would hold up to 100000 until reset
  pacer_.record(wall, sim_->time(), running);
}

void NodeTop::reset(double wall) {
  sim_->reset();
  output.trail.clear();
  fault_reported_ = false;
  pacer_.reanchor(wall, sim_->time(), false);  // time keeps running: keep the window
}

void NodeTop::reanchor(double wall, bool clear_window) { pacer_.reanchor(wall, sim_->time(), clear_window); }

void NodeTop::set_paused(bool paused, double wall) {
  if (paused == paused_) return;
  paused_ = paused;
  reanchor(wall, true);  // as ~pause does: the time paused is not debt
}

std::string NodeTop::command(const top_sim::TopCommand& m, double wall, top_sim::Command& applied) {
  std::string error;
  const top_sim::Command c = command_from_message(m, error);
  if (error.empty() && !c.empty()) error = top_sim::validate(c, m.reset ? sim_->scene().model : sim_->model());
  if (!error.empty()) return error;
  if (m.reset) reset(wall);
  if (m.set_paused) set_paused(m.paused, wall);
  if (c.empty()) return "";
  error = sim_->submit(c);  // validated above against the same model: refused only if the core's rules differ
  if (error.empty()) applied = c;
  return error;
}

std::size_t NodeTop::take_steps() {
  const std::size_t now = sim_->stats().steps;
  const std::size_t d = now - steps_reported_;
  steps_reported_ = now;
  return d;
}

void NodeTop::report(double real_time_factor, double publish_rate, bool paused) {
  if (sim_->end_state() != top_sim::EndState::none && !fault_reported_) {
    fault_reported_ = true;  // a named end, no fault: said once, as information
    ROS_INFO("top_sim_node: top %s: %s (call ~reset to run again)", name_.c_str(), sim_->end_message().c_str());
  }
  if (sim_->fault() != top_sim::ContactFault::none && !fault_reported_) {
    fault_reported_ = true;
    if (launch_top())
      ROS_ERROR("top_sim_node: contact fault, simulation stopped (call ~reset): %s", sim_->fault_message().c_str());
    else
      ROS_ERROR_THROTTLE(1.0, "top_sim_node: top %s: contact fault, stopped (call ~reset or ~kill): %s",
                         name_.c_str(), sim_->fault_message().c_str());
  }
  if (pacer_.behind() == behind_reported_) return;
  behind_reported_ = pacer_.behind();
  const double achieved = pacer_.achieved_factor();
  if (!launch_top()) {  // one line per second for all spawned tops; the diagnostics count them
    ROS_INFO_THROTTLE(1.0, "top_sim_node: top %s %s: achieved real-time factor %.3g of %.3g", name_.c_str(),
                      behind_reported_ ? "falling behind" : "caught up", achieved, real_time_factor);
  } else if (behind_reported_) {
    ROS_WARN("top_sim_node: falling behind: achieved %.3g of requested %.3g (the physics gets %.3g ms of each "
             "%.3g ms period; debt beyond %.2g s is dropped)", achieved, real_time_factor, 1e3 * pacer_.budget(),
             1e3 / publish_rate, pacer_.options().max_debt);
  } else if (paused || paused_ || sim_->stopped()) {
    ROS_INFO("top_sim_node: %s: no longer falling behind", paused || paused_                        ? "paused"
                                                            : sim_->end_state() != top_sim::EndState::none ? "ended"
                                                                                                   : "stopped by a fault");
  } else {
    ROS_INFO("top_sim_node: caught up: achieved real-time factor %.4g of requested %.4g", achieved, real_time_factor);
  }
}

}  // namespace top_sim_ros
