// make_stepper: which stepper runs a scene's method (the steppers live one per file, steppers.hpp).
#include "steppers.hpp"

#include <stdexcept>
#include <utility>

#include "dopri5.hpp"
#include "rosenbrock4.hpp"

namespace top_sim {

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
