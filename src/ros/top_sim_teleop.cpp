// Keyboard teleoperation of top_sim_node, in the spirit of turtle_teleop_key: tilt, spin, reverse, pause, reset.
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "top_sim/TopState.h"
#include "top_sim/limits.hpp"

namespace {

// Puts the terminal in non-canonical, no-echo mode and restores it on destruction (signals keep working).
class RawTerminal {
 public:
  explicit RawTerminal(int fd) : fd_(fd) {
    if (!isatty(fd_) || tcgetattr(fd_, &saved_) != 0) return;
    termios raw = saved_;
    raw.c_lflag &= ~(ICANON | ECHO);
    raw.c_cc[VMIN] = 1;
    raw.c_cc[VTIME] = 0;
    active_ = tcsetattr(fd_, TCSANOW, &raw) == 0;
  }
  ~RawTerminal() {
    if (active_) tcsetattr(fd_, TCSANOW, &saved_);
  }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;
  bool active() const { return active_; }

 private:
  int fd_;
  termios saved_{};
  bool active_ = false;
};

enum class Key { none, up, down, left, right, reverse, pause, reset, quit, end_of_input };

// Waits up to timeout_ms for a byte; returns -1 on timeout, -2 at end of input.
int read_byte(int fd, int timeout_ms) {
  pollfd p{fd, POLLIN, 0};
  const int r = poll(&p, 1, timeout_ms);
  if (r <= 0) return -1;
  unsigned char c = 0;
  const ssize_t n = read(fd, &c, 1);
  if (n <= 0) return -2;
  return c;
}

// Decodes one key press; arrow keys arrive as ESC [ A..D (or ESC O A..D in application cursor mode).
Key read_key(int fd, int timeout_ms) {
  const int c = read_byte(fd, timeout_ms);
  if (c == -2) return Key::end_of_input;
  if (c < 0) return Key::none;
  switch (c) {
    case 'q': case 'Q': return Key::quit;
    case 'r': case 'R': return Key::reverse;
    case ' ': return Key::pause;
    case '0': case 'x': case 'X': return Key::reset;
    case 'k': return Key::up;     // vi-style aliases for terminals that mangle arrow keys
    case 'j': return Key::down;
    case 'h': return Key::left;
    case 'l': return Key::right;
    case 27: break;
    default: return Key::none;
  }
  const int c1 = read_byte(fd, 50);
  if (c1 != '[' && c1 != 'O') return Key::none;
  switch (read_byte(fd, 50)) {
    case 'A': return Key::up;
    case 'B': return Key::down;
    case 'C': return Key::right;
    case 'D': return Key::left;
    default: return Key::none;
  }
}

struct Latest {
  double alpha = 0.0;
  double spin = 0.0;
  bool paused = false;
};

const char* kKeyMap =
    "Keyboard control of top_sim_node (%s)\n"
    "---------------------------------------------\n"
    "  up / down     tilt the plane: alpha +/- %.4g rad\n"
    "  right / left  spin faster / slower: |spin| +/- %.4g rad/s\n"
    "  r             reverse the spin\n"
    "  space         pause / resume\n"
    "  0 or x        reset to the scene's initial state\n"
    "  q             quit\n"
    "  (h j k l work as left down up right)\n";

struct Settings {
  std::string sim_node = "top_sim";
  double alpha_step = 0.01;  // [rad] per key press
  double spin_step = 10.0;   // [rad/s] per key press
  double max_alpha = 1.5;    // just inside the node's |alpha| < kMaxInclination bound; the node validates again
  double max_spin = 2000.0;  // [rad/s]
};

// The private parameters; false (after a fatal log) when one is out of range.
bool read_settings(ros::NodeHandle& pnh, Settings& s) {
  s.sim_node = pnh.param<std::string>("sim_node", s.sim_node);
  s.alpha_step = pnh.param("alpha_step", s.alpha_step);
  s.spin_step = pnh.param("spin_step", s.spin_step);
  s.max_alpha = pnh.param("max_inclination", s.max_alpha);
  s.max_spin = pnh.param("max_spin", s.max_spin);
  if (!(s.alpha_step > 0.0) || !(s.spin_step > 0.0) || !(s.max_alpha > 0.0 && top_sim::admissible_inclination(s.max_alpha)) ||
      !(s.max_spin > 0.0)) {
    ROS_FATAL("top_sim_teleop: alpha_step = %g (> 0 rad), spin_step = %g (> 0 rad/s), max_inclination = %g "
              "(0 < x < pi/2 rad), max_spin = %g (> 0 rad/s): a value is out of range",
              s.alpha_step, s.spin_step, s.max_alpha, s.max_spin);
    return false;
  }
  return true;
}

// Turns key presses into topics and service calls on the simulator node.
class Teleop {
 public:
  explicit Teleop(const Settings& settings) : settings_(settings), sim_(settings.sim_node) {
    inclination_pub_ = sim_.advertise<std_msgs::Float64>("inclination", 1);
    spin_pub_ = sim_.advertise<std_msgs::Float64>("spin", 1);
    pause_client_ = sim_.serviceClient<std_srvs::SetBool>("pause");
    reset_client_ = sim_.serviceClient<std_srvs::Trigger>("reset");
    state_sub_ = sim_.subscribe<top_sim::TopState>("top_state", 1, [this](const top_sim::TopState::ConstPtr& msg) {
      std::lock_guard<std::mutex> lock(mutex_);
      latest_ = Latest{msg->alpha, msg->spin, static_cast<bool>(msg->paused)};
    });
  }

  const std::string& sim_namespace() const { return sim_.getNamespace(); }

  // Reads keys until q, end of input or shutdown.
  void run() {
    while (ros::ok()) {
      const Key key = read_key(STDIN_FILENO, 100);
      if (key == Key::none) continue;
      if (key == Key::quit || key == Key::end_of_input) break;
      if (key == Key::reset) {
        reset();
        continue;
      }
      const std::optional<Latest> now = current();
      if (!now) {
        ROS_WARN("no TopState received yet on %s; key ignored", state_sub_.getTopic().c_str());
        continue;
      }
      handle(key, *now);
    }
  }

 private:
  // Commands are built on the last TopState received, so a key never undoes a change made elsewhere.
  std::optional<Latest> current() {
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_;
  }

  // Remember what was sent, so repeated keys accumulate even before the next TopState (or while paused).
  template <class Update>
  void remember(Update update) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (latest_) update(*latest_);
  }

  static void publish(ros::Publisher& pub, double value) {
    std_msgs::Float64 m;
    m.data = value;
    pub.publish(m);
  }

  void handle(Key key, const Latest& now) {
    switch (key) {
      case Key::up:
      case Key::down: tilt(key == Key::up ? settings_.alpha_step : -settings_.alpha_step, now); break;
      case Key::left:
      case Key::right: change_spin(key == Key::right ? settings_.spin_step : -settings_.spin_step, now); break;
      case Key::reverse: reverse(now); break;
      case Key::pause: toggle_pause(now); break;
      default: break;
    }
  }

  void tilt(double step, const Latest& now) {
    const double target = std::clamp(now.alpha + step, -settings_.max_alpha, settings_.max_alpha);
    publish(inclination_pub_, target);
    remember([&](Latest& l) { l.alpha = target; });
    ROS_INFO("inclination %.4f -> %.4f rad", now.alpha, target);
  }

  // Faster/slower act on the magnitude, keeping the sense of rotation; slowing stops at zero.
  void change_spin(double step, const Latest& now) {
    const double sign = now.spin < 0.0 ? -1.0 : 1.0;
    const double magnitude = std::max(0.0, std::abs(now.spin) + step);
    const double target = sign * std::min(magnitude, settings_.max_spin);
    publish(spin_pub_, target);
    remember([&](Latest& l) { l.spin = target; });
    ROS_INFO("spin %.2f -> %.2f rad/s", now.spin, target);
  }

  void reverse(const Latest& now) {
    const double target = std::clamp(-now.spin, -settings_.max_spin, settings_.max_spin);
    publish(spin_pub_, target);
    remember([&](Latest& l) { l.spin = target; });
    ROS_INFO("spin %.2f -> %.2f rad/s (reversed)", now.spin, target);
  }

  void toggle_pause(const Latest& now) {
    std_srvs::SetBool srv;
    srv.request.data = !now.paused;
    if (!pause_client_.call(srv)) {
      ROS_ERROR("pause: service %s is not available", pause_client_.getService().c_str());
    } else if (!srv.response.success) {
      ROS_WARN("%s refused: %s", srv.request.data ? "pause" : "resume", srv.response.message.c_str());
    } else {
      remember([&](Latest& l) { l.paused = srv.request.data; });
      ROS_INFO("%s: %s", srv.request.data ? "paused" : "resumed", srv.response.message.c_str());
    }
  }

  void reset() {
    std_srvs::Trigger srv;
    if (reset_client_.call(srv))
      ROS_INFO("reset: %s%s", srv.response.success ? "ok" : "refused", srv.response.message.empty() ? "" :
               (" (" + srv.response.message + ")").c_str());
    else
      ROS_ERROR("reset: service %s is not available", reset_client_.getService().c_str());
  }

  Settings settings_;
  ros::NodeHandle sim_;
  ros::Publisher inclination_pub_, spin_pub_;
  ros::ServiceClient pause_client_, reset_client_;
  ros::Subscriber state_sub_;
  std::mutex mutex_;              // latest_ is written by the spinner thread
  std::optional<Latest> latest_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "top_sim_teleop");
  ros::NodeHandle pnh("~");
  Settings settings;
  if (!read_settings(pnh, settings)) return 2;

  Teleop teleop(settings);
  ros::AsyncSpinner spinner(1);
  spinner.start();

  std::printf(kKeyMap, teleop.sim_namespace().c_str(), settings.alpha_step, settings.spin_step);
  std::fflush(stdout);

  RawTerminal terminal(STDIN_FILENO);
  if (!terminal.active())
    ROS_WARN("top_sim_teleop: stdin is not a terminal; reading keys from it as they come "
             "(run with rosrun, or launch-prefix=\"xterm -e\" under roslaunch)");
  teleop.run();
  spinner.stop();
  return 0;
}
