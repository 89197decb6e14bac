// The control panel's widget against a running node (panel.test), under QT_QPA_PLATFORM=offscreen: its buttons
// send what the node then shows in TopState and ~list.
#include <gtest/gtest.h>

#include <QApplication>
#include <QComboBox>
#include <QLineEdit>
#include <QPushButton>
#include <functional>

#include <ros/ros.h>

#include "control_panel.hpp"
#include "top_sim/ListTops.h"
#include "top_sim/TopState.h"

namespace {

top_sim::TopState g_state;
bool g_have_state = false;

void on_state(const top_sim::TopState::ConstPtr& m) {
  g_state = *m;
  g_have_state = true;
}

// Spins ROS and Qt until `done` holds or `seconds` pass.
bool wait_for(const std::function<bool()>& done, double seconds = 10.0) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end) {
    ros::spinOnce();
    QApplication::processEvents();
    if (done()) return true;
    ros::WallDuration(0.01).sleep();
  }
  return false;
}

void click(top_sim_rviz::ControlWidget& w, const char* text) {
  for (QPushButton* b : w.findChildren<QPushButton*>())
    if (b->text() == text) return b->click();
  ADD_FAILURE() << "no button " << text;
}

std::vector<std::string> tops() {
  top_sim::ListTops srv;
  return ros::service::call("/top_sim/list", srv) ? srv.response.names : std::vector<std::string>{};
}

}  // namespace

TEST(PanelWidget, ButtonsReachTheNode) {
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe("/top_sim/top_state", 10, on_state);
  ASSERT_TRUE(ros::service::waitForService("/top_sim/reset", ros::Duration(30.0)));
  top_sim_rviz::ControlWidget w;
  ASSERT_TRUE(wait_for([] { return g_have_state; }));

  w.inclination_field()->setText("0.2");
  w.spin_field()->setText("150");
  click(w, "Apply to the picked top");
  EXPECT_TRUE(wait_for([] { return g_state.alpha == 0.2 && std::abs(g_state.spin - 150.0) < 2.0; }))
      << "alpha " << g_state.alpha << ", spin " << g_state.spin << "; panel: " << w.message();

  w.inclination_field()->setText("abc");  // refused in the panel: nothing is sent
  click(w, "Apply to the picked top");
  EXPECT_EQ(w.message(), "inclination = 'abc': must be a number");
  w.inclination_field()->clear();
  w.spin_field()->clear();
  w.law_field()->setCurrentText("coulomb");
  w.parameter_field("mu")->setText("0.35");
  click(w, "Apply to the picked top");
  EXPECT_TRUE(wait_for([] { return std::abs(g_state.mu - 0.35) < 1e-12 && g_state.alpha == 0.2; }))
      << "mu " << g_state.mu << "; panel: " << w.message();

  click(w, "Pause");
  EXPECT_TRUE(wait_for([] { return g_state.paused; })) << w.message();
  click(w, "Resume");
  EXPECT_TRUE(wait_for([] { return !g_state.paused; })) << w.message();
  click(w, "Reset");
  EXPECT_TRUE(wait_for([] { return std::abs(g_state.alpha - 0.1) < 1e-12; })) << "back to the scene's 0.1: " << w.message();

  w.spawn_name_field()->setText("b");
  click(w, "Spawn");
  EXPECT_TRUE(wait_for([] { return tops().size() == 2; })) << w.message();
  ASSERT_TRUE(wait_for([&] { return w.top_field()->findText("b") >= 0; })) << "the top list follows the node";
  w.top_field()->setCurrentIndex(w.top_field()->findText("b"));
  click(w, "Kill picked");
  EXPECT_TRUE(wait_for([] { return tops() == std::vector<std::string>{"top"}; })) << w.message();
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_panel_widget");
  QApplication app(argc, argv);
  return RUN_ALL_TESTS();
}
