// The control panel's Qt-free logic (src/rviz/panel_logic.hpp): names, field text -> TopCommand with the core's
// checks, the status line. No master needed.
#include <gtest/gtest.h>

#include "panel_logic.hpp"
#include "top_sim/friction.hpp"

using top_sim_rviz::PanelFields;

TEST(PanelLogic, TopicsOfTheLaunchTimeTopAndOfSpawnedTops) {
  EXPECT_EQ(top_sim_rviz::top_name_of("/top_sim", "top", "command"), "/top_sim/command");
  EXPECT_EQ(top_sim_rviz::top_name_of("/top_sim/", "b", "command"), "/top_sim/b/command");
  EXPECT_EQ(top_sim_rviz::top_name_of("/group_b/top_sim", "", "spin"), "/group_b/top_sim/spin");
}

TEST(PanelLogic, MotionFieldsBecomeACommandAndBadTextNamesFieldAndRange) {
  PanelFields f;
  f.inclination = "0.2";
  top_sim::TopCommand c;
  EXPECT_EQ(top_sim_rviz::to_command(f, c), "");
  EXPECT_TRUE(c.set_inclination);
  EXPECT_EQ(c.inclination, 0.2);
  EXPECT_FALSE(c.set_spin);
  EXPECT_FALSE(c.set_friction);
  f.spin = "-150";
  EXPECT_EQ(top_sim_rviz::to_command(f, c), "");
  EXPECT_EQ(c.spin, -150.0);
  f.inclination = "0.2x";
  EXPECT_EQ(top_sim_rviz::to_command(f, c), "inclination = '0.2x': must be a number");
  f.inclination = "1.6";  // the core's rule, not a copy of it
  EXPECT_NE(top_sim_rviz::to_command(f, c).find("inclination = 1.6: must be finite with |alpha| < pi/2"),
            std::string::npos);
  EXPECT_NE(top_sim_rviz::to_command(PanelFields(), c).find("nothing to apply"), std::string::npos);
}

TEST(PanelLogic, FrictionFieldsGiveOnlyWhatIsFilledIn) {
  PanelFields f;
  f.friction_law = "paper";
  f.friction["mu_c"] = "0.3";
  f.friction["s_c"] = "";  // empty: the node keeps its s_c
  top_sim::TopCommand c;
  ASSERT_EQ(top_sim_rviz::to_command(f, c), "");
  EXPECT_TRUE(c.set_friction);
  EXPECT_EQ(c.friction_law, "paper");
  EXPECT_EQ(c.mu_c, 0.3);
  ASSERT_EQ(c.friction_given.size(), 1u);
  EXPECT_EQ(c.friction_given[0], "mu_c");
  f.friction["s_c"] = "1.5";
  EXPECT_NE(top_sim_rviz::to_command(f, c).find("s_c = 1.5: must be"), std::string::npos);
  f.friction_law = "table";
  EXPECT_NE(top_sim_rviz::to_command(f, c).find("but table"), std::string::npos);
}

TEST(PanelLogic, LawsAndParametersComeFromTheCoreTables) {
  const std::vector<std::string> laws = top_sim_rviz::law_names();
  std::size_t parameters = 0;
  for (const std::string& law : laws) parameters += top_sim_rviz::law_parameters(law).size();
  EXPECT_EQ(parameters, sizeof(top_sim::kFrictionParameters) / sizeof(top_sim::kFrictionParameters[0]));
  EXPECT_EQ(top_sim_rviz::law_parameters("paper"), (std::vector<std::string>{"mu_c", "s_c"}));
}

// The ring's turn about the plane's x axis adds to alpha; the other parts of a turn do not; the result is checked
// by the core (|alpha| < pi/2). The spin handle's scale: 1 cm = 20 rad/s.
TEST(PanelLogic, RingTiltsAndHandleSpins) {
  double alpha = 0.0;
  const double h = 0.5 * 0.1;  // a turn of 0.1 rad about x
  EXPECT_EQ(top_sim_rviz::inclination_from_ring(0.1, std::cos(h), std::sin(h), 0.0, 0.0, alpha), "");
  EXPECT_NEAR(alpha, 0.2, 1e-12);
  const double g = 0.5 * 0.3;  // about z only: no tilt
  EXPECT_EQ(top_sim_rviz::inclination_from_ring(0.1, std::cos(g), 0.0, 0.0, std::sin(g), alpha), "");
  EXPECT_NEAR(alpha, 0.1, 1e-12);
  const double big = 0.5 * 1.5;
  EXPECT_NE(top_sim_rviz::inclination_from_ring(0.1, std::cos(big), std::sin(big), 0.0, 0.0, alpha)
                .find("must be finite with |alpha| < pi/2"), std::string::npos);
  double spin = 0.0;
  EXPECT_EQ(top_sim_rviz::spin_from_handle(200.0, 0.01, spin), "");
  EXPECT_NEAR(spin, 220.0, 1e-9);
  EXPECT_NE(top_sim_rviz::spin_from_handle(200.0, 1000.0, spin).find("spin = 2000200"), std::string::npos);
}

TEST(PanelLogic, StatusLineShowsRegimeModePhiAndPacing) {
  top_sim::TopState s;
  s.regime = top_sim::TopState::SLEEPING;
  s.contact_mode = top_sim::TopState::SLIPPING;
  s.pose.orientation.w = 1.0;
  s.phi = 0.27;
  s.has_stationary_state = true;
  s.phi_star = 0.27;
  s.real_time_factor = 0.98;
  s.requested_real_time_factor = 1.0;
  EXPECT_EQ(top_sim_rviz::status_line(s), "sleeping, slipping, phi 0.270 / phi* 0.270, v 0.00 mm/s | real time x0.98 of 1");
  s.paused = true;
  s.requested_real_time_factor = 0.0;
  EXPECT_EQ(top_sim_rviz::status_line(s),
            "sleeping, slipping, phi 0.270 / phi* 0.270, v 0.00 mm/s | real time x0.98 of as fast as possible | paused");
  double f = 0.0;
  EXPECT_EQ(top_sim_rviz::parse_real_time_factor("2.5", f), "");
  EXPECT_EQ(f, 2.5);
  EXPECT_NE(top_sim_rviz::parse_real_time_factor("-1", f).find("real_time_factor = -1: must be >= 0"),
            std::string::npos);
}
