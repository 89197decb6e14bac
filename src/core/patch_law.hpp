// The coupled sliding and drilling law of physics.md section 12 per newton of normal force, for every contact that
// has a patch (the tip sphere in dynamics.cpp, each shape of a body of shapes in shape_motion.cpp).
#pragma once

#include <cmath>

#include "exact_law_table.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/model.hpp"

namespace top_sim {

// The coupled law of section 12 per newton of normal force at lever Rbar: F / N = -force_per_speed v_t and
// M_n / N = drilling, with s the generalised slip. Inline: a Hertz patch evaluates it twice per right-hand side.
struct PatchLaw {
  double slip, mu, force_per_speed, drilling, force_factor_per_speed;
};
[[gnu::always_inline]] inline PatchLaw patch_law(const Model& model, double lever, double slip_speed, double omega_n,
                                                 double speed_sum) {
  const double v_eps = model.regularization_speed;
  const double wy = lever * omega_n, pivot = std::abs(wy), w2 = slip_speed * slip_speed + wy * wy;
  const double inverse_w = 1.0 / std::sqrt(w2 + v_eps * v_eps);
  PatchLaw law;
  law.slip = std::sqrt(w2) / (speed_sum + pivot);
  law.mu = friction_coefficient(model.friction, law.slip);
  const FiniteContact& fc = model.finite_contact;
  const DrillingFactors k = fc.law == DrillingLaw::exact
                                ? exact_law::factors(exact_law::table(fc.pressure), slip_speed, pivot)
                                : DrillingFactors{};
  law.force_factor_per_speed = k.force * inverse_w;
  law.force_per_speed = law.mu * law.force_factor_per_speed;
  law.drilling = -law.mu * lever * k.torque * wy * inverse_w;
  return law;
}

}  // namespace top_sim
