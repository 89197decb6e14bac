// Paper Fig. 3 analogue: the gyroscope-loaded top whose shell spin is dragged through zero by its rotor
// (physics.md sections 5 and 6, scene config/scenes/gyro_reversal.yaml). Expected values are physics.md's
// analytic results, computed here from the scene's parameters, not taken from the simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../src/output/run.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;

// physics.md section 5: tan(phi*/2) = s* on the paper law's stable branch.
double paper_phi_star(double alpha, double mu_c, double s_c) {
  const double s = s_c * (1.0 - std::sqrt(1.0 - std::tan(alpha) / mu_c));
  return 2.0 * std::atan(s);
}

struct Sample {
  double t, x, y, u_y, spin;
};

class GyroReversal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(load_scene(TOP_SIM_TEST_CONFIG_DIR "/scenes/gyro_reversal.yaml"));
    Simulator sim(*scene_);
    // Dense sampling (1 kHz): the flip takes a fraction of a second.
    const double dt = 1e-3;
    samples_ = new std::vector<Sample>();
    for (long k = 0; k <= static_cast<long>(std::lround(scene_->duration / dt)); ++k) {
      sim.advance_to(k * dt);
      const Snapshot s = sim.snapshot();
      samples_->push_back({s.t, s.contact_point.x(), s.contact_point.y(), s.tip_velocity.y(), s.spin});
      ASSERT_EQ(s.fault, ContactFault::none) << s.fault_message;
    }
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete samples_;
  }
  // Direction of travel of the contact point between two sample times.
  static double phi_between(double t0, double t1) {
    const Sample& a = at(t0);
    const Sample& b = at(t1);
    return travel_angle(b.x - a.x, b.y - a.y);
  }
  static const Sample& at(double t) { return (*samples_)[static_cast<std::size_t>(std::lround(t / 1e-3))]; }

  static Scene* scene_;
  static std::vector<Sample>* samples_;
};

Scene* GyroReversal::scene_ = nullptr;
std::vector<Sample>* GyroReversal::samples_ = nullptr;

TEST_F(GyroReversal, SceneIsTheDocumentedAssembly) {
  const Model& m = scene_->model;
  ASSERT_TRUE(m.top.has_rotor);
  EXPECT_DOUBLE_EQ(m.plane.inclination, 0.07);
  EXPECT_DOUBLE_EQ(scene_->initial.spin, -20.0);
  EXPECT_DOUBLE_EQ(scene_->initial.rotor_spin, 2000.0);
  // physics.md section 6: the shell spin reverses only if I_f' omega_t + J Omega > 0.
  const double J = m.top.rotor.inertia_axial, I_fs = m.top.inertia_axial - J;
  EXPECT_GT(I_fs * scene_->initial.spin + J * scene_->initial.rotor_spin, 0.0);
}

TEST_F(GyroReversal, PathFlipsFromPiMinusPhiStarToPhiStar) {
  const Model& m = scene_->model;
  const double phi_star = paper_phi_star(m.plane.inclination, m.friction.mu_c, m.friction.s_c);
  // Tolerance 2e-3 rad (the issue asks for 1e-2): the leftover precession wobbles phi by about 2e-4.
  const double before = phi_between(5.0, 15.0);  // shell spin negative: path at pi - phi*
  const double after = phi_between(35.0, 60.0);  // shell spin positive: path at phi*
  EXPECT_NEAR(before, M_PI - phi_star, 2e-3);
  EXPECT_NEAR(after, phi_star, 2e-3);
  // Not time-reversal: the horizontal motion flips, phi_f = pi - phi_i.
  EXPECT_NEAR(after, M_PI - before, 2e-3);
}

TEST_F(GyroReversal, DownhillMotionNeverReverses) {
  // Downhill is -y in the plane frame: the contact point's velocity keeps u_y < 0 at every sample and
  // its y coordinate falls monotonically, through the flip as well.
  double max_u_y = -1.0;
  int rises = 0;
  for (std::size_t i = 0; i < samples_->size(); ++i) {
    max_u_y = std::max(max_u_y, (*samples_)[i].u_y);
    if (i > 0 && (*samples_)[i].y >= (*samples_)[i - 1].y) ++rises;
  }
  EXPECT_LT(max_u_y, 0.0);
  EXPECT_EQ(rises, 0);
}

TEST_F(GyroReversal, ShellSpinCrossesZeroWhenTheBearingPredicts) {
  // Bearing only (section 6): J Omega' = -c nu, I_f' omega_t' = c nu, so nu decays at
  // lambda = c (1/J + 1/I_f') and omega_t(t) = omega_0 + (c nu_0 / I_f') (1 - exp(-lambda t)) / lambda.
  const Model& m = scene_->model;
  const double J = m.top.rotor.inertia_axial, c = m.top.rotor.coupling, I_fs = m.top.inertia_axial - J;
  const double w0 = scene_->initial.spin, nu0 = scene_->initial.rotor_spin - w0;
  const double lambda = c * (1.0 / J + 1.0 / I_fs);
  const double t_zero = -std::log(1.0 - lambda * (-w0 * I_fs / (c * nu0))) / lambda;
  double t_cross = -1.0;
  for (const Sample& s : *samples_)
    if (s.spin >= 0.0) {
      t_cross = s.t;
      break;
    }
  ASSERT_GT(t_cross, 0.0) << "the shell spin never reversed";
  // 1 %: the estimate neglects the friction torque about the figure axis.
  EXPECT_NEAR(t_cross, t_zero, 0.01 * t_zero);
  EXPECT_NEAR(t_zero, 20.0, 1.0);  // the "after about 20 s"
}

}  // namespace
