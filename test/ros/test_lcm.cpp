// rostest (lcm.test): top_sim.top_state_t arrives over LCM from the node; a node whose LCM cannot open logs
// one clear error and keeps publishing on ROS.
#include <gtest/gtest.h>

#include <string>
#include <ros/ros.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <rosgraph_msgs/Log.h>

#include "top_sim/TopState.h"
#include "top_sim/top_state_t.hpp"

namespace {

std::string g_url, g_channel;

struct Handler {
  std::vector<top_sim::top_state_t> received;
  void on(const lcm::ReceiveBuffer*, const std::string&, const top_sim::top_state_t* m) { received.push_back(*m); }
};

TEST(Lcm, NodeStateArrivesOnTheChannel) {
  lcm::LCM lcm(g_url);
  ASSERT_TRUE(lcm.good()) << "receiver cannot open " << g_url
                          << " (a multicast route is needed: ip route add 224.0.0.0/4 dev lo)";
  Handler h;
  lcm.subscribe(g_channel, &Handler::on, &h);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (h.received.size() < 20 && ros::WallTime::now() < end) lcm.handleTimeout(100);
  ASSERT_GE(h.received.size(), 20u) << "messages on " << g_channel;
  for (std::size_t i = 1; i < h.received.size(); ++i) EXPECT_GT(h.received[i].utime, h.received[i - 1].utime);
  const top_sim::top_state_t& m = h.received.back();
  EXPECT_EQ(m.alpha, 0.1);  // config/scenes/default.yaml
  EXPECT_NEAR(std::hypot(std::hypot(m.figure_axis[0], m.figure_axis[1]), m.figure_axis[2]), 1.0, 1e-9);
  const double q = std::sqrt(m.orientation[0] * m.orientation[0] + m.orientation[1] * m.orientation[1] +
                             m.orientation[2] * m.orientation[2] + m.orientation[3] * m.orientation[3]);
  EXPECT_NEAR(q, 1.0, 1e-9);
  EXPECT_GT(m.spin, 150.0);  // started at 200 rad/s, decays slowly
  EXPECT_GE(int(m.regime), int(top_sim::top_state_t::NUTATING));  // int(): the constants have no definition
  EXPECT_LE(int(m.regime), int(top_sim::top_state_t::CONTACT_FAULT));
  EXPECT_GT(m.real_time_factor, 0.5);
  // Contact mode: the code and its name agree; the gap is 0 in contact and positive only in flight.
  const std::string names[] = {"slipping", "rolling", "flight"};
  ASSERT_GE(int(m.contact_mode), int(top_sim::top_state_t::SLIPPING));
  ASSERT_LE(int(m.contact_mode), int(top_sim::top_state_t::FLIGHT));
  EXPECT_EQ(m.contact_mode_name, names[int(m.contact_mode)]);
  EXPECT_GE(m.gap, 0.0);
  if (int(m.contact_mode) != int(top_sim::top_state_t::FLIGHT)) EXPECT_EQ(m.gap, 0.0);
  // The default top has no shapes: its tip sphere is bit 0 while it touches; it has no end state.
  EXPECT_EQ(m.touching, int(m.contact_mode) == int(top_sim::top_state_t::FLIGHT) ? 0 : 1);
  EXPECT_EQ(m.end_state, "");
  EXPECT_EQ(m.end_state_message, "");
}

TEST(Lcm, UnopenableUrlIsReportedAndRosKeepsPublishing) {
  ros::NodeHandle nh;
  std::mutex mu;
  std::vector<std::string> errors;  // ERRORs from the node while we listen: the start-up one may precede us
  std::string lcm_diagnostic;
  ros::Subscriber log = nh.subscribe<rosgraph_msgs::Log>("/rosout", 100, [&](const rosgraph_msgs::Log::ConstPtr& m) {
    if (m->name == "/top_sim_bad_lcm" && m->level >= rosgraph_msgs::Log::ERROR) {
      std::lock_guard<std::mutex> lock(mu);
      errors.push_back(m->msg);
    }
  });
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& a) {
        for (const auto& st : a->status)
          if (st.name.find("top_sim_bad_lcm") != std::string::npos)
            for (const auto& kv : st.values)
              if (kv.key == "lcm") {
                std::lock_guard<std::mutex> lock(mu);
                lcm_diagnostic = kv.value;
              }
      });
  std::size_t n = 0;
  ros::Subscriber st = nh.subscribe<top_sim::TopState>("/top_sim_bad_lcm/top_state", 100,
                                                       [&](const top_sim::TopState::ConstPtr&) { ++n; });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while ((n < 400 || lcm_diagnostic.empty()) && ros::WallTime::now() < end) ros::WallDuration(0.01).sleep();
  EXPECT_GE(n, 400u) << "the node with a bad lcm_url must keep publishing on ROS (2 s at 200 Hz)";
  std::lock_guard<std::mutex> lock(mu);
  EXPECT_NE(lcm_diagnostic.find("error: LCM cannot open 'udpm://300.1.2.3:7667?ttl=0'"), std::string::npos)
      << "diagnostics 'lcm' = '" << lcm_diagnostic << "'";
  EXPECT_LE(errors.size(), 1u) << "one error, not one per publish";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "top_sim_lcm_test");
  ros::NodeHandle pnh("~");
  pnh.param("url", g_url, std::string("udpm://239.255.76.67:7668?ttl=0"));
  pnh.param("channel", g_channel, std::string("TOP_STATE_TEST"));
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
