// The control panel's Qt-free logic (src/rviz/panel_logic.hpp): names, field text -> TopCommand with the core's
// checks, the status line. No master needed.
#include <gtest/gtest.h>

#include <cmath>

#include "control_layout.hpp"
#include "panel_logic.hpp"
#include "top_sim/format.hpp"
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
  EXPECT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_TRUE(c.set_inclination);
  EXPECT_EQ(c.inclination, 0.2);
  EXPECT_FALSE(c.set_spin);
  EXPECT_FALSE(c.set_friction);
  f.spin = "-150";
  EXPECT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_EQ(c.spin, -150.0);
  f.inclination = "0.2x";
  EXPECT_EQ(top_sim_rviz::fields_to_message(f, c), "inclination = '0.2x': must be a number");
  f.inclination = "1.6";  // the core's rule, not a copy of it
  EXPECT_NE(top_sim_rviz::fields_to_message(f, c).find("inclination = 1.6: must be finite with |alpha| < pi/2"),
            std::string::npos);
  EXPECT_EQ(top_sim_rviz::refused_message(top_sim_rviz::fields_to_message(PanelFields(), c)),
            "Nothing was sent: no value was typed in and no friction law picked.");
}

// Patch, rolling resistance and air: only the filled-in fields are sent, each checked by the core (its range).
TEST(PanelLogic, ContactFieldsGiveOnlyWhatIsFilledInAndTheCoreChecksThem) {
  PanelFields f;
  f.contact["patch_radius"] = "2e-4";
  f.contact["spin_drag"] = "";  // empty: not sent
  top_sim::TopCommand c;
  ASSERT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_TRUE(c.set_patch_radius);
  EXPECT_EQ(c.patch_radius, 2e-4);
  EXPECT_FALSE(c.set_spin_drag || c.set_rolling_resistance || c.set_drag || c.set_inclination || c.set_friction);
  const std::string a = top_sim::format_number(2e-4);  // numbers as every message prints them
  EXPECT_EQ(top_sim_rviz::sent_message(c, "top"), "Sent to top 'top': patch_radius " + a + " m.");
  f.contact["drag"] = "1e-6";
  ASSERT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_EQ(top_sim_rviz::sent_message(c, "top"),
            "Sent to top 'top': patch_radius " + a + " m and drag " + top_sim::format_number(1e-6) + " N s/m.");
  f.contact["patch_radius"] = "-1";
  EXPECT_NE(top_sim_rviz::fields_to_message(f, c).find("patch_radius = -1: must be in [0, 1] m"), std::string::npos)
      << top_sim_rviz::fields_to_message(f, c);
  f.contact["patch_radius"] = "wide";
  EXPECT_EQ(top_sim_rviz::fields_to_message(f, c), "patch_radius = 'wide': must be a number");
}

TEST(PanelLogic, FrictionFieldsGiveOnlyWhatIsFilledIn) {
  PanelFields f;
  f.friction_law = "paper";
  f.friction["mu_c"] = "0.3";
  f.friction["s_c"] = "";  // empty: the node keeps its s_c
  top_sim::TopCommand c;
  ASSERT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_TRUE(c.set_friction);
  EXPECT_EQ(c.friction_law, "paper");
  EXPECT_EQ(c.mu_c, 0.3);
  ASSERT_EQ(c.friction_given.size(), 1u);
  EXPECT_EQ(c.friction_given[0], "mu_c");
  f.friction["s_c"] = "1.5";
  EXPECT_NE(top_sim_rviz::fields_to_message(f, c).find("s_c = 1.5: must be"), std::string::npos);
  f.friction_law = "table";
  EXPECT_NE(top_sim_rviz::fields_to_message(f, c).find("but table"), std::string::npos);
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

// What the panel says is plain sentences: capitalised, a full stop, what was sent to which top.
TEST(PanelLogic, MessagesAreSentences) {
  EXPECT_EQ(top_sim_rviz::sentence("paused"), "Paused.");
  EXPECT_EQ(top_sim_rviz::sentence("  reset top 'top' to its start at t = 3 s; time keeps running forward \n"),
            "Reset top 'top' to its start at t = 3 s; time keeps running forward.");
  EXPECT_EQ(top_sim_rviz::sentence("Done."), "Done.");
  EXPECT_EQ(top_sim_rviz::sentence(" "), "");
  PanelFields f;
  f.inclination = "0.2";
  f.spin = "150";
  top_sim::TopCommand c;
  ASSERT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_EQ(top_sim_rviz::sent_message(c, "b"), "Sent to top 'b': inclination 0.2 rad and spin 150 rad/s.");
  f.friction_law = "linearized";
  f.friction["mu0"] = "0.25";
  f.friction["k"] = "1";
  ASSERT_EQ(top_sim_rviz::fields_to_message(f, c), "");
  EXPECT_EQ(top_sim_rviz::sent_message(c, "top"),
            "Sent to top 'top': inclination 0.2 rad, spin 150 rad/s and friction law linearized with mu0 0.25 and "
            "k 1.");
  EXPECT_EQ(top_sim_rviz::refused_message("inclination = 'abc': must be a number"),
            "Nothing was sent: inclination = 'abc': must be a number.");
  EXPECT_EQ(top_sim_rviz::service_message("/top_sim/reset", false, false, ""),
            "The service /top_sim/reset did not answer; is the node running?");
  EXPECT_EQ(top_sim_rviz::service_message("/top_sim/pause", true, true, ""), "Done.");
  EXPECT_EQ(top_sim_rviz::service_message("/top_sim/kill", true, false, "no top named 'x'"), "No top named 'x'.");
}

// A field follows the picked top's value until the user edits it: focus or typed text keeps the user's text,
// Apply (or clearing the text) hands it back to the top's value.
TEST(PanelLogic, FieldsFollowTheTopUnlessEdited) {
  top_sim_rviz::FollowedField alpha;  // exact: a value sent as 0.15 reads back as "0.15"
  EXPECT_EQ(alpha.follow(0.1, false).value_or("kept"), "0.1");
  EXPECT_EQ(alpha.follow(0.15, false).value_or("kept"), "0.15");  // e.g. an inclination sent by topic
  EXPECT_FALSE(alpha.follow(0.2, true).has_value()) << "a field with the focus keeps its text";
  alpha.typed("0.3");
  EXPECT_TRUE(alpha.edited());
  EXPECT_FALSE(alpha.follow(0.2, false).has_value()) << "typed and not applied: the user's text stays";
  alpha.applied();
  EXPECT_FALSE(alpha.edited());
  EXPECT_EQ(alpha.follow(0.3, false).value_or("kept"), "0.3");
  alpha.typed("0.25");
  alpha.typed("  ");  // cleared: nothing to send, follow the top again
  EXPECT_FALSE(alpha.edited());
  EXPECT_EQ(alpha.follow(0.3, false).value_or("kept"), "0.3");
  EXPECT_FALSE(alpha.follow(std::nan(""), false).has_value()) << "no NaN shown";
  top_sim_rviz::FollowedField spin(1);  // a spin that keeps changing: one decimal
  EXPECT_EQ(spin.follow(199.8765, false).value_or("kept"), "199.9");
  EXPECT_EQ(top_sim_rviz::field_text(-150.0, 1), "-150.0");
  EXPECT_EQ(top_sim_rviz::field_text(2.5, -1), "2.5");
}

// A scene's view hint as rviz's orbit camera: low from the side, top from above, follow as the shipped config; the
// hint's distance, or the camera's own when the hint has none; nothing for an unset or unknown camera.
TEST(PanelLogic, ViewHintBecomesAnOrbitCamera) {
  using top_sim_rviz::orbit_view;
  ASSERT_TRUE(orbit_view("low", 0.15, 0.27));
  EXPECT_LT(orbit_view("low", 0.15, 0.27)->pitch, 0.2);
  EXPECT_EQ(orbit_view("low", 0.15, 0.27)->distance, 0.15);
  EXPECT_GT(orbit_view("top", 0.0, 0.27)->pitch, 1.3);
  EXPECT_EQ(orbit_view("top", 0.0, 0.27)->distance, 0.27);
  EXPECT_EQ(orbit_view("follow", 0.0, 0.3)->pitch, 0.55);
  EXPECT_FALSE(orbit_view("unset", 0.2, 0.27));
  EXPECT_FALSE(orbit_view("side", 0.2, 0.27));
}

// The low camera close to a small body (tippe_top_stem's hint: 0.15 m) keeps the plane and the label over the body
// and its controls inside the vertical field of view: at 0.15 m looking 12 mm up the label was above the view.
TEST(PanelLogic, LowViewShowsTheLabel) {
  using top_sim_rviz::orbit_view;
  for (const double reach : {0.0, 0.036, 0.08, 0.2}) {
    const auto v = orbit_view("low", 0.15, 0.27, reach);
    ASSERT_TRUE(v);
    const double half = v->distance * std::tan(0.5 * top_sim_rviz::kFieldOfView);  // seen above and below focal_z
    EXPECT_LE(v->focal_z + 0.0 - half, 0.0) << "plane cut off, reach " << reach;
    EXPECT_GE(v->focal_z + half, top_sim_rviz::label_top(reach)) << "label cut off, reach " << reach;
    EXPECT_GE(v->distance, 0.15);
  }
  EXPECT_GT(top_sim_rviz::label_top(0.0), top_sim_ros::control_layout::kTop);
}
