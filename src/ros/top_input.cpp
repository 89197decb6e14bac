#include "top_input.hpp"

#include "conversions.hpp"

namespace top_sim_ros {

void RejectionLog::warn(const std::string& text, double wall) {
  ++total_;
  flush(wall);  // a pending count goes out first (and starts a new second)
  if (wall - last_warn_ >= kPeriod) {
    ROS_WARN("top_sim_node: %s", text.c_str());
    last_warn_ = wall;
    suppressed_ = 0;
  } else {
    ++suppressed_;
    last_text_ = text;
  }
}

void RejectionLog::flush(double wall) {
  if (suppressed_ == 0 || wall - last_warn_ < kPeriod) return;
  ROS_WARN("top_sim_node: %zu more commands rejected in the last %.1f s (warnings suppressed); the last: %s",
           suppressed_, wall - last_warn_, last_text_.c_str());
  last_warn_ = wall;
  suppressed_ = 0;
}

TopInput::TopInput(ros::NodeHandle& nh, const std::string& prefix, const std::string& top_name, SubmitCommand submit,
                   ApplyMessage apply, RejectionLog& log)
    : label_(prefix.empty() ? "" : "top " + top_name + ": "),
      name_(top_name),
      submit_(std::move(submit)),
      apply_(std::move(apply)),
      log_(log) {
  // No Nagle delay on commands: their latency is part of the contract (two publish periods).
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  inclination_ = nh.subscribe(prefix + "inclination", kQueue, &TopInput::on_inclination, this, hints);
  spin_ = nh.subscribe(prefix + "spin", kQueue, &TopInput::on_spin, this, hints);
  command_ = nh.subscribe(prefix + "command", kQueue, &TopInput::on_command, this, hints);
}

void TopInput::submit(const top_sim::Command& c, const char* source) {
  const std::string error = submit_(c);
  if (!error.empty()) log_.warn(label_ + source + " rejected: " + error, ros::WallTime::now().toSec());
}

void TopInput::on_inclination(const std_msgs::Float64::ConstPtr& m) {
  top_sim::Command c;
  c.inclination = m->data;
  submit(c, "inclination");
}

void TopInput::on_spin(const std_msgs::Float64::ConstPtr& m) {
  top_sim::Command c;
  c.spin = m->data;
  submit(c, "spin");
}

void TopInput::on_command(const top_sim::TopCommand::ConstPtr& m) {
  std::string error;
  if (!m->name.empty() && m->name != name_)  // a command meant for another top is never applied to this one
    error = "name = '" + m->name + "': this topic is top '" + name_ + "''s own: name must be empty or '" + name_ +
            "' (~tops/command takes any top)";
  else
    error = apply_(*m);
  if (!error.empty()) log_.warn(label_ + "command rejected: " + error, ros::WallTime::now().toSec());
}

}  // namespace top_sim_ros
