// Instructions per right-hand side, point contact against the finite contact of physics.md section 12 (issue 32:
// at most 1.3x). Counts, not times: run under valgrind, which counts only inside measured_loop:
//   valgrind --tool=callgrind --toggle-collect='*measured_loop*' --callgrind-out-file=OUT rhs_counts CASE N
// and divide callgrind_annotate's total by N. CASE: point | fixed_patch | hertz | hertz_elliptic | every_term.
// The state is the default scene's at 0.37 s (nutating: every term is non-trivial), as in core_bench.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "top_sim/dynamics.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;

[[gnu::noinline]] void measured_loop(const Model& model, const StateVector& y, StateVector& dydt, long n) {
  const ContactModel contact = contact_model(model);  // decided once, as the Simulator does at each restart
  for (long i = 0; i < n; ++i) {
    model_derivative(model, contact, ContactMode::slipping, y, dydt);
    asm volatile("" : : "r"(dydt.data()) : "memory");  // keeps every call
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rhs_counts point|fixed_patch|hertz|hertz_elliptic|every_term N\n");
    return 2;
  }
  const std::string which = argv[1];
  const long n = std::atol(argv[2]);
  Scene scene = load_scene(default_config_dir() + "/scenes/default.yaml");
  StateVector y;
  {
    Simulator sim(scene);
    sim.advance_to(0.37);
    y = sim.state();
  }
  FiniteContact& fc = scene.model.finite_contact;
  if (which == "fixed_patch") {
    fc.patch_radius = 1.0e-4;
  } else if (which != "point") {
    fc.hertz = true;
    fc.effective_modulus = effective_modulus({6.9e10, 0.33}, {3.0e9, 0.37});  // aluminium on PMMA
    if (which == "hertz_elliptic") fc.law = DrillingLaw::elliptic;
    if (which == "every_term") {
      fc.rolling_resistance = 1.0e-5;
      scene.model.air.spin_drag = 1.0e-8;
      scene.model.air.drag = 1.0e-3;
    } else if (which != "hertz" && which != "hertz_elliptic") {
      std::fprintf(stderr, "rhs_counts: unknown case '%s'\n", which.c_str());
      return 2;
    }
  }
  StateVector dydt{};
  model_derivative(scene.model, ContactMode::slipping, y, dydt);  // the exact law's table, outside the count
  measured_loop(scene.model, y, dydt, n);
  std::printf("%s: dydt[omega] = %.17g %.17g %.17g\n", which.c_str(), dydt[idx::omega], dydt[idx::omega + 1],
              dydt[idx::omega + 2]);
  return 0;
}
