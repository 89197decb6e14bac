// Energy balance E + W_diss (physics.md section 4).
#include "energy.hpp"

#include <cmath>

#include "rigid_body.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {
// f_hat is the state's figure axis normalised (the caller's, so that it is normalised once).
[[gnu::always_inline]] inline double kinetic_energy(const Model& model, const StateVector& y, const Eigen::Vector3d& f_hat) {
  const Top& top = model.top;
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double nu = top.has_rotor ? y[idx::nu] : 0.0;
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d v_cm = velocity3(y) + w.cross(top.com_offset * f_hat);
  const double Omega = w.dot(f_hat) + nu;
  return detail::body_kinetic_energy(top, v_cm, f_hat, w) + 0.5 * J * Omega * Omega;
}
}  // namespace

double mechanical_energy(const Model& model, const StateVector& y) {
  if (has_shapes(model)) [[unlikely]]
    return shape_mechanical_energy(model, y);
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d r_cm =
      Eigen::Vector3d(y[idx::x], y[idx::x + 1], top.tip_radius + y[idx::gap]) + top.com_offset * f_hat;
  return kinetic_energy(model, y, f_hat) - top.mass * model.plane.g_plane.dot(r_cm);  // m g z_cm,W = -m g_P . r_cm
}

double energy_scale(const Model& model, const StateVector& y) {
  const Top& top = model.top;
  if (has_shapes(model)) [[unlikely]]
    return shape_energy_scale(model, y);
  return kinetic_energy(model, y, figure_axis(y).normalized()) +
         top.mass * model.plane.gravity * (top.tip_radius + std::abs(top.com_offset));
}

void EnergyBalance::rebase(const Model& model, const StateVector& y) {
  reference = mechanical_energy(model, y) + y[idx::w_diss];
  scale = energy_scale(model, y);
  if (!(scale > 0.0)) scale = 1.0;
}

double EnergyBalance::residual(double energy, const StateVector& y) const {
  return std::abs(energy + y[idx::w_diss] - reference) / scale;
}

}  // namespace top_sim
