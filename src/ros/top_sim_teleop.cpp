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

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "top_sim_teleop");
  ros::NodeHandle pnh("~");

  std::string sim_node = pnh.param<std::string>("sim_node", "top_sim");
  const double alpha_step = pnh.param("alpha_step", 0.01);
  const double spin_step = pnh.param("spin_step", 10.0);
  // Just inside the node's |alpha| < pi/2 bound; the node validates again.
  const double max_alpha = pnh.param("max_inclination", 1.5);
  const double max_spin = pnh.param("max_spin", 2000.0);
  if (!(alpha_step > 0.0) || !(spin_step > 0.0) || !(max_alpha > 0.0 && max_alpha < M_PI / 2) || !(max_spin > 0.0)) {
    ROS_FATAL("top_sim_teleop: alpha_step = %g (> 0 rad), spin_step = %g (> 0 rad/s), max_inclination = %g "
              "(0 < x < pi/2 rad), max_spin = %g (> 0 rad/s): a value is out of range",
              alpha_step, spin_step, max_alpha, max_spin);
    return 2;
  }

  ros::NodeHandle sim(sim_node);
  ros::Publisher inclination_pub = sim.advertise<std_msgs::Float64>("inclination", 1);
  ros::Publisher spin_pub = sim.advertise<std_msgs::Float64>("spin", 1);
  ros::ServiceClient pause_client = sim.serviceClient<std_srvs::SetBool>("pause");
  ros::ServiceClient reset_client = sim.serviceClient<std_srvs::Trigger>("reset");

  std::mutex mutex;
  std::optional<Latest> latest;
  ros::Subscriber state_sub = sim.subscribe<top_sim::TopState>(
      "top_state", 1, [&](const top_sim::TopState::ConstPtr& msg) {
        std::lock_guard<std::mutex> lock(mutex);
        latest = Latest{msg->alpha, msg->spin, static_cast<bool>(msg->paused)};
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();

  std::printf(kKeyMap, sim.getNamespace().c_str(), alpha_step, spin_step);
  std::fflush(stdout);

  RawTerminal terminal(STDIN_FILENO);
  if (!terminal.active())
    ROS_WARN("top_sim_teleop: stdin is not a terminal; reading keys from it as they come "
             "(run with rosrun, or launch-prefix=\"xterm -e\" under roslaunch)");

  // Commands are built on the last TopState received, so a key never undoes a change made elsewhere.
  auto current = [&]() {
    std::lock_guard<std::mutex> lock(mutex);
    return latest;
  };
  // Remember what was sent, so repeated keys accumulate even before the next TopState (or while paused).
  auto remember = [&](auto update) {
    std::lock_guard<std::mutex> lock(mutex);
    if (latest) update(*latest);
  };
  auto publish = [](ros::Publisher& pub, double value) {
    std_msgs::Float64 m;
    m.data = value;
    pub.publish(m);
  };

  while (ros::ok()) {
    const Key key = read_key(STDIN_FILENO, 100);
    if (key == Key::none) continue;
    if (key == Key::quit || key == Key::end_of_input) break;

    if (key == Key::reset) {
      std_srvs::Trigger srv;
      if (reset_client.call(srv))
        ROS_INFO("reset: %s%s", srv.response.success ? "ok" : "refused", srv.response.message.empty() ? "" :
                 (" (" + srv.response.message + ")").c_str());
      else
        ROS_ERROR("reset: service %s is not available", reset_client.getService().c_str());
      continue;
    }

    const std::optional<Latest> now = current();
    if (!now) {
      ROS_WARN("no TopState received yet on %s; key ignored", state_sub.getTopic().c_str());
      continue;
    }

    switch (key) {
      case Key::up:
      case Key::down: {
        const double target = std::clamp(now->alpha + (key == Key::up ? alpha_step : -alpha_step), -max_alpha, max_alpha);
        publish(inclination_pub, target);
        remember([&](Latest& l) { l.alpha = target; });
        ROS_INFO("inclination %.4f -> %.4f rad", now->alpha, target);
        break;
      }
      case Key::left:
      case Key::right: {
        // Faster/slower act on the magnitude, keeping the sense of rotation; slowing stops at zero.
        const double sign = now->spin < 0.0 ? -1.0 : 1.0;
        const double magnitude = std::max(0.0, std::abs(now->spin) + (key == Key::right ? spin_step : -spin_step));
        const double target = sign * std::min(magnitude, max_spin);
        publish(spin_pub, target);
        remember([&](Latest& l) { l.spin = target; });
        ROS_INFO("spin %.2f -> %.2f rad/s", now->spin, target);
        break;
      }
      case Key::reverse: {
        const double target = std::clamp(-now->spin, -max_spin, max_spin);
        publish(spin_pub, target);
        remember([&](Latest& l) { l.spin = target; });
        ROS_INFO("spin %.2f -> %.2f rad/s (reversed)", now->spin, target);
        break;
      }
      case Key::pause: {
        std_srvs::SetBool srv;
        srv.request.data = !now->paused;
        if (!pause_client.call(srv)) {
          ROS_ERROR("pause: service %s is not available", pause_client.getService().c_str());
        } else if (!srv.response.success) {
          ROS_WARN("%s refused: %s", srv.request.data ? "pause" : "resume", srv.response.message.c_str());
        } else {
          remember([&](Latest& l) { l.paused = srv.request.data; });
          ROS_INFO("%s: %s", srv.request.data ? "paused" : "resumed", srv.response.message.c_str());
        }
        break;
      }
      default:
        break;
    }
  }
  spinner.stop();
  return 0;
}
