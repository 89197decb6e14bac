// Command handling: a top's command topics (inclination, spin, command) turned into core Commands, and the
// node-wide, throttled log of rejected commands (docs/ros.md, "Commands"). The core validates; a rejected command
// leaves the top untouched.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "top_sim/TopCommand.h"
#include "top_sim/command.hpp"

namespace top_sim_ros {

// Rejected-command warnings: the first in full, then at most one per wall second naming the last rejection and
// counting those suppressed since (a flood of bad commands must not flood /rosout).
class RejectionLog {
 public:
  void warn(const std::string& text, double wall);
  void flush(double wall);  // a pending count goes out once its second is over
  std::size_t total() const { return total_; }

 private:
  static constexpr double kPeriod = 1.0;  // wall seconds between warnings
  double last_warn_ = -1e9;
  std::size_t suppressed_ = 0, total_ = 0;
  std::string last_text_;
};

// Submits a command to a top; returns "" or the core's reason for refusing it.
using SubmitCommand = std::function<std::string(const top_sim::Command&)>;
// Applies a whole TopCommand (reset, pause, the core's fields) to a top; returns "" or why nothing was applied.
using ApplyMessage = std::function<std::string(const top_sim::TopCommand&)>;

// The three command topics of one top under `nh` + `prefix` ("" for the launch-time top, "NAME/" for a spawned one).
// A TopCommand's `name` there is empty or the top's own.
class TopInput {
 public:
  TopInput(ros::NodeHandle& nh, const std::string& prefix, const std::string& top_name, SubmitCommand submit,
           ApplyMessage apply, RejectionLog& log);

 private:
  void submit(const top_sim::Command& c, const char* source);
  void on_inclination(const std_msgs::Float64::ConstPtr& m);
  void on_spin(const std_msgs::Float64::ConstPtr& m);
  void on_command(const top_sim::TopCommand::ConstPtr& m);

  static constexpr uint32_t kQueue = 100;  // a 1 kHz stream is 5 per 200 Hz tick; 10 dropped 0.24 % of a flood
  std::string label_;                      // "" or "top NAME: " in warnings
  std::string name_;
  SubmitCommand submit_;
  ApplyMessage apply_;
  RejectionLog& log_;
  ros::Subscriber inclination_, spin_, command_;
};

}  // namespace top_sim_ros
