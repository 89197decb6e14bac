// top_sim_interactive: interactive markers for every top of a top_sim_node (docs/ros.md, "Control in rviz"): a
// ring to tilt the plane, a handle to set the spin, a menu with pause/resume, reset and kill. A thin client of the
// node's topics and services, like the panel; a separate node so that the simulator's loop never waits on rviz.
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "control_layout.hpp"
#include "panel_logic.hpp"
#include "top_sim/Kill.h"
#include "top_sim/TopCommand.h"
#include "top_sim/TopStateArray.h"

namespace {

using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::InteractiveMarkerFeedback;

// Where the controls rest in the top's contact frame: beside the top (plane +x) and clear of a body that reaches
// `reach` from its contact point, small, not over its body or label.
geometry_msgs::Pose rest_pose(double reach) {
  geometry_msgs::Pose p;
  p.position.x = top_sim_ros::control_layout::offset_x(reach);
  p.position.z = top_sim_ros::control_layout::kHeight;
  p.orientation.w = 1.0;
  return p;
}

// `description`: rviz shows it on hover and draws it as the button of a MENU control without markers; rviz logs an
// ERROR for every empty one, so each control says what it does.
InteractiveMarkerControl control(const std::string& name, const std::string& description, int mode, double w,
                                 double x, double y, double z) {
  InteractiveMarkerControl c;
  c.name = name;
  c.description = description;
  c.interaction_mode = mode;
  c.orientation.w = w;
  c.orientation.x = x;
  c.orientation.y = y;
  c.orientation.z = z;
  return c;
}

// The menu's own handle, a small sphere at the ring's centre: with a marker of its own rviz does not draw the
// description as a floating text button beside the top.
InteractiveMarkerControl menu_button(const std::string& top, double scale) {
  InteractiveMarkerControl c = control("menu", "Right-click for the menu of top " + top +
                                                   ": Pause, Resume, Reset and Kill.",
                                       InteractiveMarkerControl::MENU, 1.0, 0.0, 0.0, 0.0);
  c.always_visible = true;
  visualization_msgs::Marker sphere;
  sphere.type = visualization_msgs::Marker::SPHERE;
  sphere.scale.x = sphere.scale.y = sphere.scale.z = 0.25 * scale;
  sphere.color.r = sphere.color.g = sphere.color.b = 0.8f;
  sphere.color.a = 1.0f;
  sphere.pose.orientation.w = 1.0;
  c.markers.push_back(sphere);
  return c;
}

class InteractiveTops {
 public:
  explicit InteractiveTops(const std::string& node) : node_(node), server_(ros::this_node::getName()) {
    ros::param::param<std::string>(node_ + "/contact_frame", contact_frame_, "contact");
    menu_.insert("Pause", [this](const InteractiveMarkerFeedback::ConstPtr&) { pause(true); });
    menu_.insert("Resume", [this](const InteractiveMarkerFeedback::ConstPtr&) { pause(false); });
    menu_.insert("Reset", [this](const InteractiveMarkerFeedback::ConstPtr&) { reset(); });
    menu_.insert("Kill", [this](const InteractiveMarkerFeedback::ConstPtr& f) { kill(top_of(f->marker_name)); });
    states_ = nh_.subscribe(node_ + "/top_states", 1, &InteractiveTops::on_states, this);
  }

 private:
  struct Latest {
    double alpha = 0.0, spin = 0.0;
  };

  static std::string top_of(const std::string& marker) { return marker.substr(0, marker.rfind('/')); }

  std::string frame_of(const std::string& top) const {
    return top == top_sim_rviz::kLaunchTopName ? contact_frame_ : top + "/" + contact_frame_;
  }

  // The tops come and go with spawn and kill: one marker each.
  void on_states(const top_sim::TopStateArray::ConstPtr& a) {
    std::set<std::string> now;
    for (std::size_t i = 0; i < a->names.size() && i < a->states.size(); ++i) {
      now.insert(a->names[i]);
      latest_[a->names[i]] = {a->states[i].alpha, a->states[i].spin};
      if (!shown_.count(a->names[i])) add(a->names[i]);
    }
    for (auto it = shown_.begin(); it != shown_.end();) {
      if (now.count(*it)) {
        ++it;
        continue;
      }
      server_.erase(*it + "/controls");
      latest_.erase(*it);
      it = shown_.erase(it);
    }
    server_.applyChanges();
  }

  void add(const std::string& top) {
    InteractiveMarker m;
    m.header.frame_id = frame_of(top);
    m.name = top + "/controls";
    m.description = top + ": ring tilts the plane, arrow sets the spin (1 cm = " +
                    std::to_string(static_cast<int>(top_sim_rviz::kSpinPerMetre / 100.0)) + " rad/s)";
    m.scale = top_sim_ros::control_layout::kScale;
    ros::param::get(node_ + "/view/reach", reach_);  // set by the node at start; up by now, its tops are
    m.pose = rest_pose(reach_);
    const double r = std::sqrt(0.5);  // control orientations: their x axis is the axis they act along
    m.controls.push_back(control("tilt", "Turn the ring and release to tilt the plane of top " + top + ".",
                                 InteractiveMarkerControl::ROTATE_AXIS, 1.0, 0.0, 0.0, 0.0));  // plane x
    m.controls.push_back(control("spin", "Drag the arrow and release to change the spin of top " + top + ".",
                                 InteractiveMarkerControl::MOVE_AXIS, r, 0.0, -r, 0.0));  // normal
    m.controls.push_back(menu_button(top, m.scale));
    server_.insert(m, [this](const InteractiveMarkerFeedback::ConstPtr& f) { on_feedback(f); });
    menu_.apply(server_, m.name);
    shown_.insert(top);
  }

  // On release: the ring's turn or the handle's drag becomes one command; the marker returns to its rest pose.
  void on_feedback(const InteractiveMarkerFeedback::ConstPtr& f) {
    if (f->event_type != InteractiveMarkerFeedback::MOUSE_UP) return;
    const std::string top = top_of(f->marker_name);
    const Latest now = latest_[top];
    top_sim::TopCommand c;
    std::string error;
    if (f->control_name == "tilt") {
      const auto& q = f->pose.orientation;
      error = top_sim_rviz::inclination_from_ring(now.alpha, q.w, q.x, q.y, q.z, c.inclination);
      c.set_inclination = true;
    } else if (f->control_name == "spin") {
      error = top_sim_rviz::spin_from_handle(now.spin, f->pose.position.z - rest_pose(reach_).position.z, c.spin);
      c.set_spin = true;
    } else {
      return;
    }
    if (error.empty()) send(top, c);
    else ROS_WARN("top_sim_interactive: top %s: %s (not sent)", top.c_str(), error.c_str());
    server_.setPose(f->marker_name, rest_pose(reach_));
    server_.applyChanges();
  }

  void send(const std::string& top, top_sim::TopCommand c) {
    c.name = top;  // ~tops/command steers any top, with or without its own topics (~per_top_topics)
    const std::string topic = top_sim_rviz::top_name_of(node_, "", "tops/command");
    auto it = commands_.find(topic);
    if (it == commands_.end()) {
      it = commands_.emplace(topic, nh_.advertise<top_sim::TopCommand>(topic, 10, true)).first;
      ros::WallDuration(0.2).sleep();  // the node connects before the first message
    }
    it->second.publish(c);
  }

  void pause(bool on) {
    std_srvs::SetBool srv;
    srv.request.data = on;
    if (!ros::service::call(node_ + "/pause", srv)) ROS_WARN("top_sim_interactive: %s/pause did not answer", node_.c_str());
  }

  void reset() {
    std_srvs::Trigger srv;
    if (!ros::service::call(node_ + "/reset", srv)) ROS_WARN("top_sim_interactive: %s/reset did not answer", node_.c_str());
  }

  void kill(const std::string& top) {
    top_sim::Kill srv;
    srv.request.name = top;
    if (!ros::service::call(node_ + "/kill", srv) || !srv.response.success)
      ROS_WARN("top_sim_interactive: kill %s: %s", top.c_str(), srv.response.message.c_str());
  }

  std::string node_, contact_frame_;
  double reach_ = 0.0;  // [m] the launch-time top's body from its contact point (~view/reach)
  ros::NodeHandle nh_;
  interactive_markers::InteractiveMarkerServer server_;
  interactive_markers::MenuHandler menu_;
  ros::Subscriber states_;
  std::map<std::string, ros::Publisher> commands_;
  std::map<std::string, Latest> latest_;
  std::set<std::string> shown_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "top_sim_interactive");
  std::string node;
  ros::param::param<std::string>("~node", node, "/top_sim");
  InteractiveTops tops(node);
  ros::spin();
  return 0;
}
