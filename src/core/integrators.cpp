// Method names and their kinds. Which stepper runs a method: make_stepper (steppers.cpp).
#include "top_sim/integrators.hpp"

#include <string>

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

}  // namespace top_sim
