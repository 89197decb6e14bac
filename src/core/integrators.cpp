// Method names and make_stepper: which stepper runs a scene's method. The steppers live one per file (steppers.hpp).
#include "top_sim/integrators.hpp"

#include <stdexcept>
#include <string>

#include "dopri5.hpp"
#include "rosenbrock4.hpp"
#include "steppers.hpp"

namespace top_sim {

const char* to_string(Method m) {
  switch (m) {
    case Method::euler: return "euler";
    case Method::semi_implicit_euler: return "semi_implicit_euler";
    case Method::rk4: return "rk4";
    case Method::dopri5: return "dopri5";
    case Method::rosenbrock4: return "rosenbrock4";
    case Method::switching: return "switching";
    case Method::implicit_midpoint: return "implicit_midpoint";
    case Method::fitted_midpoint: return "fitted_midpoint";
  }
  return "?";
}

bool parse_method(const std::string& name, Method& out) {
  for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::dopri5, Method::rosenbrock4,
                   Method::switching, Method::implicit_midpoint, Method::fitted_midpoint})
    if (name == to_string(m)) {
      out = m;
      return true;
    }
  return false;
}

bool is_adaptive(Method m) { return m == Method::dopri5 || m == Method::rosenbrock4 || m == Method::switching; }

namespace {

std::unique_ptr<Stepper> make_plain_stepper(const IntegratorSettings& settings, System system,
                                            DifferenceSteps difference_steps, Azimuth azimuth = {}) {
  switch (settings.method) {
    case Method::euler:
    case Method::semi_implicit_euler:
    case Method::rk4:
    case Method::implicit_midpoint:
    case Method::fitted_midpoint:
      return make_fixed_stepper(settings.method, settings.dt, std::move(system), std::move(difference_steps),
                                std::move(azimuth));
    case Method::dopri5:
      return std::make_unique<Dopri5Stepper>(settings, std::move(system));
    case Method::rosenbrock4:
      return std::make_unique<Rosenbrock4Stepper>(settings, std::move(system), std::move(difference_steps));
    case Method::switching:
      return make_switching_stepper(settings, std::move(system), std::move(difference_steps));
  }
  throw std::invalid_argument("make_stepper: unknown method");
}

}  // namespace

std::unique_ptr<Stepper> make_stepper(const IntegratorSettings& settings, System system,
                                      DifferenceSteps difference_steps, StiffLayer in_layer, Azimuth azimuth) {
  if (!in_layer || settings.method == Method::rosenbrock4)
    return make_plain_stepper(settings, std::move(system), std::move(difference_steps), std::move(azimuth));
  IntegratorSettings stiff = settings;
  stiff.method = Method::rosenbrock4;
  stiff.dt = kLayerFirstStep;
  return make_layered_stepper(make_plain_stepper(settings, system, difference_steps, std::move(azimuth)),
                              make_plain_stepper(stiff, system, difference_steps), std::move(in_layer));
}

}  // namespace top_sim
