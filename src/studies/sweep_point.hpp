// One point of top_sim_sweep: build the scene, simulate until sleeping (or sliding), measure phi.
// Used by top_sim_sweep and by the paper tests, so the figures and the tests run the same code.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "run.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"

namespace top_sim {

enum class SweepStart {
  tilted,    // the standard start: figure axis tilted, contact point at rest (slip s = 1 at t = 0)
  launched,  // the sleeping state's velocity, its tilt + launch_perturbation: starts near s*, not s = 1
};

// contact.patch_radius of a point (physics.md section 12): a fixed radius, or hertz (from N and the materials).
struct PatchRadius {
  double metres = 0.0;  // 0 = the point contact
  bool hertz = false;
};

// The patch radius as its CSV column and its --patch-radius item print it: hertz, or the number.
std::string patch_radius_text(const PatchRadius& patch);

// What to simulate at one grid point; unset optionals keep the values of the named files.
struct SweepPoint {
  std::string top = "aluminium";  // name in <config>/tops, or a path to a .yaml file
  std::string plane = "pmma";     // name in <config>/planes, or a path to a .yaml file
  double alpha = 0.1;             // inclination [rad]
  double spin = 200.0;            // initial shell spin [rad/s]
  std::optional<double> mu_c;     // paper law override
  std::optional<double> s_c;      // paper law override
  PatchRadius patch;              // contact.patch_radius (default: the point contact)
};

// How every point is simulated.
struct SweepSettings {
  std::string config_dir;          // "" = default_config_dir()
  SweepStart start = SweepStart::tilted;
  double tilt = 0.1;               // initial tilt from the world vertical [rad] (tilted start)
  double launch_perturbation = 0.01;  // extra tilt beyond the sleeping one [rad] (launched start)
  double max_path = 40.0;          // give up after this sleeping-path length [m] (relaxation is a path length)
  double min_duration = 30.0;      // never give up before this [s]
  double max_duration = 20000.0;   // never simulate longer than this [s]
  double slide_duration = 30.0;    // run length when sliding [s]; also how long sliding must persist
  double phi_tolerance = 1.0e-6;   // converged when successive windows' phi differ by less [rad]
  double window_path = 0.5;        // window length as a sleeping-path length [m]
};

struct SweepResult {
  SweepPoint point;
  double mu_c = 0.0, s_c = 0.0;    // the paper law in effect (NaN for other laws)
  double tan_alpha = 0.0;
  double s_stable = -1.0;          // analytic stable root of mu(s) = tan(alpha), < 0 when none
  double s_unstable = -1.0;        // analytic unstable root, < 0 when none
  std::optional<double> phi_star;  // analytic phi* (signed by the spin), when a stationary state exists
  std::optional<double> phi;       // measured direction of travel at the end of the run
  std::optional<double> tan_half;  // measured tan(phi/2), mirrored for negative spin (comparable to s*)
  std::string outcome;             // sleeping | sliding | unconverged | contact_fault | an end state (fallen)
  Regime regime = Regime::nutating;
  double sim_seconds = 0.0;
  double cpu_seconds = 0.0;
  unsigned long long steps = 0, rhs_evaluations = 0;
  std::string note;                // contact-fault message etc.
};

// The scene of one grid point (throws SceneError naming the offending key).
Scene make_sweep_scene(const SweepPoint& point, const SweepSettings& settings);

// Simulates one grid point with the core's Simulator and run().
SweepResult run_sweep_point(const SweepPoint& point, const SweepSettings& settings);

void write_sweep_header(std::ostream& os);
void write_sweep_row(std::ostream& os, const SweepResult& r);

}  // namespace top_sim
