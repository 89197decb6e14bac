// rostests of the node's pacing (docs/ros.md, "Time"): whatever the scene costs, top_state keeps the publish rate
// and the services answer at once; a scene the CPU cannot keep up with is reported (TopState.real_time_factor,
// WARN on /diagnostics).
//   pacing_coulomb.test: default scene, then a TopCommand switching to Coulomb friction (mu 0.3, the scene's tiny
//                        v_eps): stiff for the explicit method; plus the throttling of rejected-command warnings.
//   pacing_slow.test:    rk4 with dt 1e-8: below 0.01 of real time with half a core; then a reachable factor.
// Rates are asserted with generous margins (>= 90 % of the publish rate); measured values are recorded as
// properties and printed.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <rosgraph_msgs/Log.h>
#include <std_msgs/Float64.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "top_sim/TopCommand.h"
#include "top_sim/TopState.h"

namespace {

const std::string kNode = "/top_sim";
double g_rate = 200.0;
double g_seconds = 4.0;

struct Received {
  top_sim::TopState msg;
  double wall;
};

struct Status {
  int level;
  std::string message;
  double wall;
};

class Monitor {
 public:
  Monitor() {
    const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    state_sub_ = nh_.subscribe(kNode + "/top_state", 5000, &Monitor::on_state, this, hints);
    diag_sub_ = nh_.subscribe("/diagnostics", 100, &Monitor::on_diag, this);
    log_sub_ = nh_.subscribe("/rosout", 1000, &Monitor::on_log, this);
    command_ = nh_.advertise<top_sim::TopCommand>(kNode + "/command", 100, true);
    inclination_ = nh_.advertise<std_msgs::Float64>(kNode + "/inclination", 100);
  }

  std::vector<Received> states_between(double w0, double w1) {
    std::lock_guard<std::mutex> lock(m_);
    std::vector<Received> out;
    for (const auto& r : states_)
      if (r.wall >= w0 && r.wall < w1) out.push_back(r);
    return out;
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(m_);
    return states_.size();
  }
  bool wait_state(std::function<bool(const top_sim::TopState&)> pred, std::size_t since, double timeout) {
    std::unique_lock<std::mutex> lock(m_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout), [&] {
      for (std::size_t i = since; i < states_.size(); ++i)
        if (pred(states_[i].msg)) return true;
      return false;
    });
  }
  // Waits for a diagnostics status of the node at `level` whose message contains `text`.
  bool wait_status(int level, const std::string& text, double timeout, Status* found, double since = 0.0) {
    std::unique_lock<std::mutex> lock(m_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout), [&] {
      for (const auto& s : statuses_)
        if (s.wall >= since && s.level == level && s.message.find(text) != std::string::npos) {
          *found = s;
          return true;
        }
      return false;
    });
  }
  std::vector<std::string> warnings_since(double wall) {
    std::lock_guard<std::mutex> lock(m_);
    std::vector<std::string> out;
    for (const auto& w : warnings_)
      if (w.second >= wall) out.push_back(w.first);
    return out;
  }

  void command(const top_sim::TopCommand& c) { command_.publish(c); }
  void inclination(double a) {
    std_msgs::Float64 m;
    m.data = a;
    inclination_.publish(m);
  }
  std::size_t inclination_subscribers() { return inclination_.getNumSubscribers(); }

 private:
  void on_state(const top_sim::TopState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(m_);
    states_.push_back({*m, ros::WallTime::now().toSec()});
    cv_.notify_all();
  }
  void on_diag(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(m_);
    for (const auto& s : m->status)
      if (s.name.find("simulation") != std::string::npos)
        statuses_.push_back({s.level, s.message, ros::WallTime::now().toSec()});
    cv_.notify_all();
  }
  void on_log(const rosgraph_msgs::Log::ConstPtr& m) {
    if (m->name != kNode || m->level < rosgraph_msgs::Log::WARN) return;
    std::lock_guard<std::mutex> lock(m_);
    warnings_.emplace_back(m->msg, ros::WallTime::now().toSec());
    cv_.notify_all();
  }

  ros::NodeHandle nh_;
  ros::Subscriber state_sub_, diag_sub_, log_sub_;
  ros::Publisher command_, inclination_;
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<Received> states_;
  std::vector<Status> statuses_;
  std::vector<std::pair<std::string, double>> warnings_;
};

Monitor* g_monitor = nullptr;

// Wall seconds a service call took (negative: the call failed).
double timed_pause(bool pause) {
  std_srvs::SetBool s;
  s.request.data = pause;
  const double w0 = ros::WallTime::now().toSec();
  if (!ros::service::call(kNode + "/pause", s) || !s.response.success) return -1.0;
  return ros::WallTime::now().toSec() - w0;
}

double timed_reset() {
  std_srvs::Trigger t;
  const double w0 = ros::WallTime::now().toSec();
  if (!ros::service::call(kNode + "/reset", t) || !t.response.success) return -1.0;
  return ros::WallTime::now().toSec() - w0;
}

struct Window {
  double rate = 0.0;             // messages per wall second received
  double sim_per_wall = 0.0;     // simulated seconds per wall second, from the messages' sim_time
  double reported_factor = 0.0;  // TopState.real_time_factor of the last message
  double requested_factor = 0.0;
  std::size_t messages = 0;
  bool sim_time_monotonic = true;
};

// Records `seconds` of top_state.
Window measure(double seconds) {
  const double w0 = ros::WallTime::now().toSec();
  ros::WallDuration(seconds).sleep();
  const double w1 = ros::WallTime::now().toSec();
  const auto v = g_monitor->states_between(w0, w1);
  Window w;
  w.messages = v.size();
  w.rate = v.size() / (w1 - w0);
  if (v.size() >= 2) {
    w.sim_per_wall = (v.back().msg.sim_time - v.front().msg.sim_time) / (v.back().wall - v.front().wall);
    w.reported_factor = v.back().msg.real_time_factor;
    w.requested_factor = v.back().msg.requested_real_time_factor;
  }
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i].msg.sim_time < v[i - 1].msg.sim_time) w.sim_time_monotonic = false;
  return w;
}

void report(const char* what, const Window& w) {
  testing::Test::RecordProperty(std::string(what) + "_rate_hz", std::to_string(w.rate));
  testing::Test::RecordProperty(std::string(what) + "_real_time_factor", std::to_string(w.reported_factor));
  std::printf("%s: top_state %.1f Hz (publish_rate %.0f), TopState.real_time_factor %.4g, simulated/wall %.4g\n",
              what, w.rate, g_rate, w.reported_factor, w.sim_per_wall);
}

void expect_services_answer_quickly(const char* what) {
  const double p = timed_pause(true);
  const double r = timed_pause(false);
  const double z = timed_reset();
  EXPECT_GE(p, 0.0) << what << ": ~pause true failed";
  EXPECT_GE(r, 0.0) << what << ": ~pause false failed";
  EXPECT_GE(z, 0.0) << what << ": ~reset failed";
  EXPECT_LT(p, 1.0) << what << ": ~pause true took [s]";
  EXPECT_LT(r, 1.0) << what << ": ~pause false took [s]";
  EXPECT_LT(z, 1.0) << what << ": ~reset took [s]";
  testing::Test::RecordProperty(std::string(what) + "_service_max_ms", std::to_string(1e3 * std::max({p, r, z})));
  std::printf("%s: ~pause %.1f ms, resume %.1f ms, ~reset %.1f ms\n", what, 1e3 * p, 1e3 * r, 1e3 * z);
}

TEST(PacingCoulomb, CoulombCommandKeepsThePublishRateAndServicesAnswer) {
  ASSERT_TRUE(ros::service::waitForService(kNode + "/reset", ros::Duration(10.0)));
  top_sim::TopCommand c;
  c.set_friction = true;
  c.friction_law = "coulomb";
  c.mu = 0.3;
  const std::size_t n = g_monitor->count();
  g_monitor->command(c);
  // Coulomb in force: mu = 0.3 while slipping, or rolling (mu_s defaults to mu(0) = 0.3; the scene's paper law has
  // mu(0) = 0, so the top never rolls before the command).
  ASSERT_TRUE(g_monitor->wait_state(
      [](const top_sim::TopState& s) {
        return std::abs(s.mu - 0.3) < 1e-12 || s.contact_mode == top_sim::TopState::ROLLING;
      },
      n, 3.0))
      << "the Coulomb law never showed in TopState (mu 0.3 or rolling)";
  const Window w = measure(g_seconds);
  report("coulomb", w);
  EXPECT_GE(w.rate, 0.9 * g_rate);
  EXPECT_TRUE(w.sim_time_monotonic);
  EXPECT_GT(w.sim_per_wall, 0.0) << "simulated time must move";
  EXPECT_EQ(w.requested_factor, 1.0);
  expect_services_answer_quickly("coulomb");  // the reset restores the scene's paper law
  const Window after = measure(1.0);
  EXPECT_GE(after.rate, 0.9 * g_rate);
}

TEST(PacingCoulomb, RejectedCommandWarningsAreThrottled) {
  for (int i = 0; i < 50 && g_monitor->inclination_subscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
  ASSERT_GT(g_monitor->inclination_subscribers(), 0u);
  const double w0 = ros::WallTime::now().toSec();
  for (int i = 0; i < 40; ++i) {  // 40 invalid inclinations within 0.4 s
    g_monitor->inclination(1.6);
    ros::WallDuration(0.01).sleep();
  }
  ros::WallDuration(2.0).sleep();  // the suppressed ones are counted in a warning at most a second later
  std::size_t full = 0, summaries = 0, suppressed = 0;
  for (const auto& w : g_monitor->warnings_since(w0)) {
    if (w.find("inclination = 1.6") == std::string::npos) continue;
    if (w.find("more commands rejected") != std::string::npos) {
      ++summaries;
      suppressed += std::stoul(w.substr(w.find("top_sim_node: ") + 14));
    } else {
      ++full;
    }
  }
  EXPECT_EQ(full, 1u) << "the first rejection in full, once";
  EXPECT_GE(summaries, 1u);
  EXPECT_LE(summaries, 3u) << "at most one warning per second";
  EXPECT_EQ(full + suppressed, 40u) << "every rejection is counted";
  // The node keeps publishing.
  const Window w = measure(1.0);
  EXPECT_GE(w.rate, 0.9 * g_rate);
}

TEST(PacingSlow, SceneTooCostlyKeepsTheRateAndReportsTheAchievedFactor) {
  ASSERT_TRUE(ros::service::waitForService(kNode + "/reset", ros::Duration(10.0)));
  ros::WallDuration(1.5).sleep();  // the achieved-factor window fills
  const Window w = measure(g_seconds);
  report("rk4_dt_1e-8", w);
  EXPECT_GE(w.rate, 0.9 * g_rate);
  EXPECT_TRUE(w.sim_time_monotonic);
  EXPECT_EQ(w.requested_factor, 1.0);
  EXPECT_GT(w.reported_factor, 0.0) << "simulated time still moves";
  EXPECT_LT(w.reported_factor, 0.5) << "rk4 at dt 1e-8 cannot run in real time";
  EXPECT_NEAR(w.reported_factor, w.sim_per_wall, 0.5 * w.sim_per_wall + 1e-3)
      << "TopState.real_time_factor is the achieved factor";
  Status s;
  ASSERT_TRUE(g_monitor->wait_status(diagnostic_msgs::DiagnosticStatus::WARN, "falling behind", 5.0, &s))
      << "no WARN 'falling behind' on /diagnostics";
  EXPECT_NE(s.message.find("of requested 1"), std::string::npos) << s.message;
  std::printf("diagnostics: %s\n", s.message.c_str());
  expect_services_answer_quickly("rk4_dt_1e-8");

  // A requested factor the CPU can reach (0.001: about 0.3 ms of physics per 5 ms tick) brings it back to OK.
  dynamic_reconfigure::Reconfigure rc;
  dynamic_reconfigure::DoubleParameter f;
  f.name = "real_time_factor";
  f.value = 0.001;
  rc.request.config.doubles.push_back(f);
  ASSERT_TRUE(ros::service::call(kNode + "/set_parameters", rc)) << "dynamic_reconfigure set_parameters";
  const double changed = ros::WallTime::now().toSec();
  Status ok;
  ASSERT_TRUE(g_monitor->wait_status(diagnostic_msgs::DiagnosticStatus::OK, "running", 6.0, &ok, changed))
      << "no OK on /diagnostics after the requested factor became reachable";
  const Window w2 = measure(2.0);
  report("rk4_dt_1e-8_factor_0.001", w2);
  EXPECT_EQ(w2.requested_factor, 0.001);
  EXPECT_NEAR(w2.reported_factor, 0.001, 0.0002);
  EXPECT_GE(w2.rate, 0.9 * g_rate);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "top_sim_pacing_test");
  ros::NodeHandle nh, pnh("~");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::param::param(kNode + "/publish_rate", g_rate, 200.0);
  pnh.param("seconds", g_seconds, 4.0);
  Monitor monitor;
  g_monitor = &monitor;
  if (!ros::topic::waitForMessage<top_sim::TopState>(kNode + "/top_state", ros::Duration(20.0))) {
    ADD_FAILURE() << kNode << "/top_state: no message within 20 s";
    return 1;
  }
  const int rc = RUN_ALL_TESTS();
  g_monitor = nullptr;
  return rc;
}
