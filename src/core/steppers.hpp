// The steppers behind make_stepper (steppers.cpp), one file each: fixed_stepper.cpp, dopri5.cpp,
// rosenbrock4.cpp, switching_stepper.cpp, layered_stepper.cpp.
#pragma once

#include <memory>

#include "top_sim/integrators.hpp"

namespace top_sim {

// euler, semi_implicit_euler, rk4, implicit_midpoint, fitted_midpoint: fixed steps landing on requested times.
std::unique_ptr<Stepper> make_fixed_stepper(Method method, double dt, System system, DifferenceSteps difference_steps,
                                            Azimuth azimuth);
// dopri5 with rosenbrock4 where it advances more simulated time per cost.
std::unique_ptr<Stepper> make_switching_stepper(const IntegratorSettings& settings, System system,
                                                DifferenceSteps difference_steps);
// `primary` outside the stiff layer, `layer` (rosenbrock4) inside it.
std::unique_ptr<Stepper> make_layered_stepper(std::unique_ptr<Stepper> primary, std::unique_ptr<Stepper> layer,
                                              StiffLayer in_layer);

}  // namespace top_sim
