// Helpers shared by the core tests: scene loading, analytic references of physics.md, finiteness checks.
#pragma once

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/output/writers.hpp"
#include "finite_fields.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim_test {

inline std::string config_dir() { return TOP_SIM_TEST_CONFIG_DIR; }
inline std::string scene_path(const std::string& name) { return config_dir() + "/scenes/" + name + ".yaml"; }
// Fixtures live next to config/ in the source tree: <source>/test/scenes/.
inline std::string fixture_path(const std::string& name) {
  return config_dir() + "/../test/scenes/" + name + ".yaml";
}

// The frictionless top of bench/peer_mujoco (config/scenes/frictionless.yaml) with a method, its dt (first step of an
// adaptive one) and rtol, atol = rtol / 100.
inline top_sim::Scene frictionless_scene(top_sim::Method method, double dt, double rtol) {
  top_sim::Scene s = top_sim::load_scene(scene_path("frictionless"));
  s.integrator.method = method;
  s.integrator.dt = dt;
  s.integrator.rtol = rtol;
  s.integrator.atol = 1e-2 * rtol;
  return s;
}

// A scene from YAML text; `source` plays the file name in error messages.
inline top_sim::Scene scene_from(const std::string& yaml, const std::string& source = "inline_scene.yaml") {
  return top_sim::parse_scene(YAML::Load(yaml), source, config_dir());
}

// Full precision, so a scene written from a computed value (e.g. alpha_c - 1e-3) is that value.
inline std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

// The standard start of the issue: aluminium top, paper law (mu_c 0.25, s_c 0.6), 0.1 rad tilt, `spin`.
inline std::string standard_scene(double alpha, double spin, const std::string& extra = "") {
  return "top: aluminium\n"
         "plane: {inclination: " + num(alpha) + "}\n"
         "friction: {law: paper, mu_c: 0.25, s_c: 0.6}\n"
         "initial: {start: tilted, tilt: 0.1, spin: " + num(spin) + "}\n" + extra;
}

// physics.md section 5, paper law, stable branch: s* = s_c (1 - sqrt(1 - tan(alpha)/mu_c)).
inline double paper_slip_star(double alpha, double mu_c, double s_c) {
  return s_c * (1.0 - std::sqrt(1.0 - std::tan(alpha) / mu_c));
}
// phi* = 2 atan(s*) for positive spin.
inline double paper_phi_star(double alpha, double mu_c, double s_c) {
  return 2.0 * std::atan(paper_slip_star(alpha, mu_c, s_c));
}


// A run sampled at `rate` per simulated second; every sample is checked for non-finite fields.
struct CheckedRun {
  top_sim::RunResult result;
  int samples = 0;
  std::string nonfinite;  // "t = ...: fields" of the first bad sample, empty when none
  std::vector<top_sim::Snapshot> snapshots;  // kept only when requested
};

inline CheckedRun run_checked(top_sim::Simulator& sim, double duration, double rate = 10.0,
                              bool keep = false) {
  CheckedRun out;
  top_sim::RunOptions opt;
  opt.duration = duration;
  opt.sample_rate = rate;
  opt.on_sample = [&out, keep](const top_sim::Snapshot& s) {
    ++out.samples;
    const std::string bad = nonfinite_fields(s);
    if (!bad.empty() && out.nonfinite.empty()) out.nonfinite = "t = " + std::to_string(s.t) + ": " + bad;
    if (keep) out.snapshots.push_back(s);
  };
  out.result = top_sim::run(sim, opt);
  const std::string bad = nonfinite_fields(out.result.final);
  if (!bad.empty() && out.nonfinite.empty()) out.nonfinite = "final: " + bad;
  return out;
}

// A measured number for the log (the report quotes them); never a pass/fail criterion by itself.
inline void note(const std::string& what, double value) {
  std::cout << "[ measured ] " << what << " = " << std::setprecision(6) << value << std::endl;
}

// Smallest angle between two directions [rad].
inline double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace top_sim_test
