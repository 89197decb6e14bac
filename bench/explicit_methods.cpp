// Why an explicit method cannot keep the frictionless top's nutation for much less work than dopri5 does
// (docs/performance.md, "MuJoCo side by side"): right-hand sides against the contact point's error for odeint's
// dopri5, Cash-Karp 5(4) and Fehlberg 7(8) over an rtol ladder and classical RK4 over a dt ladder, on the scene's
// full-model slipping right-hand side (no events: the frictionless contact never switches), plus the stability
// functions on the imaginary axis at the nutation frequency. Counts and errors, no times: the same on any machine.
//   explicit_methods [SCENE]   (default config/scenes/frictionless.yaml; markdown on stdout)
// Copying odeint's error steppers into make_controlled trips GCC's -Wuninitialized on their scratch members.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/numeric/odeint.hpp>
#pragma GCC diagnostic pop
#include <algorithm>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "top_sim/data_path.hpp"  // default_config_dir
#include "top_sim/dynamics.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

namespace odeint = boost::numeric::odeint;
using top_sim::StateVector;
using Path = std::vector<Eigen::Vector2d>;

constexpr double kObserve = 0.05;  // observation interval [s]: coarse, so that it barely shortens steps

struct Problem {
  top_sim::Model model;
  StateVector y0{};
  std::vector<double> times;
  mutable long rhs = 0;
  void operator()(const StateVector& y, StateVector& dydt, double) const {
    ++rhs;
    top_sim::derivative(model, top_sim::ContactMode::slipping, y, dydt);
  }
};

struct Run {
  Path path;
  long rhs = 0;
  std::size_t steps = 0;
};

template <class Stepper>
Run run(const Problem& p, Stepper stepper, double dt) {
  Run r;
  StateVector y = p.y0;
  p.rhs = 0;
  auto observe = [&r](const StateVector& s, double) { r.path.emplace_back(s[0], s[1]); };
  r.steps = odeint::integrate_times(stepper, std::cref(p), y, p.times.begin(), p.times.end(), dt, observe);
  r.rhs = p.rhs;
  return r;
}

double max_error(const Path& a, const Path& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return a.size() == b.size() ? e : NAN;
}

template <class Stepper>
Run controlled(const Problem& p, double rtol) {
  return run(p, odeint::make_controlled(rtol / 100.0, rtol, Stepper()), 1e-4);  // atol = rtol / 100 as elsewhere
}

void print_row(const char* method, const char* setting, const Run& r, const Path& ref) {
  std::printf("| %s | %s | %zu | %ld | %.3g |\n", method, setting, r.steps, r.rhs, 1e3 * max_error(r.path, ref));
}

void print_ladders(const Problem& p, const Path& ref) {
  std::printf("| method | setting | steps | right-hand sides | max contact-point error [mm] |\n|---|---|---|---|---|\n");
  char setting[32];
  for (double rtol : {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 1e-5, 1e-6}) {
    std::snprintf(setting, sizeof setting, "rtol %g", rtol);
    print_row("dopri5", setting, controlled<odeint::runge_kutta_dopri5<StateVector>>(p, rtol), ref);
    print_row("cash_karp54", setting, controlled<odeint::runge_kutta_cash_karp54<StateVector>>(p, rtol), ref);
    print_row("fehlberg78", setting, controlled<odeint::runge_kutta_fehlberg78<StateVector>>(p, rtol), ref);
  }
  for (double dt : {1e-3, 2e-3, 4e-3, 8e-3}) {
    std::snprintf(setting, sizeof setting, "dt %g", dt);
    print_row("rk4", setting, run(p, odeint::runge_kutta4<StateVector>(), dt), ref);
  }
}

// |R(iy)| of the propagated solution: RK4's Taylor polynomial, dopri5's with its sixth-degree term z^6 / 600.
void print_stability() {
  std::printf("\n| y = h w | abs R(iy), rk4 | abs R(iy), dopri5 |\n|---|---|---|\n");
  for (double y : {0.5, 1.0, 1.44, 2.0, 2.5, 2.83, 3.0}) {
    const std::complex<double> z(0.0, y);
    const std::complex<double> r4 = 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
    const std::complex<double> r5 = r4 + std::pow(z, 5) / 120.0 + std::pow(z, 6) / 600.0;
    std::printf("| %g | %.6f | %.6f |\n", y, std::abs(r4), std::abs(r5));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : top_sim::default_config_dir() + "/scenes/frictionless.yaml";
  const top_sim::Scene scene = top_sim::load_scene(path);
  const top_sim::Simulator sim(scene);
  Problem p{sim.model(), sim.state(), {}};
  for (double t = 0.0; t <= scene.duration + 1e-12; t += kObserve) p.times.push_back(t);
  const Run ref = controlled<odeint::runge_kutta_fehlberg78<StateVector>>(p, 1e-11);
  const Run check = controlled<odeint::runge_kutta_dopri5<StateVector>>(p, 1e-11);
  std::printf("%s, %g s, observed every %g s; reference fehlberg78 rtol 1e-11 (%ld right-hand sides; dopri5 rtol "
              "1e-11 differs by %.2g mm)\n\n", path.c_str(), scene.duration, kObserve, ref.rhs,
              1e3 * max_error(check.path, ref.path));
  print_ladders(p, ref.path);
  print_stability();
}
