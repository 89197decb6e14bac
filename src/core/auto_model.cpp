// model.kind auto (physics.md section 7.1): the handover from the full to the reduced model.
#include "auto_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <Eigen/LU>
#include <cmath>
#include <sstream>

#include "top_sim/adiabatic.hpp"
#include "top_sim/format.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

namespace {


// Index of the eigenvalue nearest `target`.
Eigen::Index nearest(const Eigen::VectorXcd& values, Eigenvalue target) {
  Eigen::Index best = 0;
  (values.array() - target).abs().minCoeff(&best);
  return best;
}

// The offset and persisting maps from the Jacobian's eigenvectors: a decaying mode c e^(lambda t) v moves the
// contact point by -c v_u / lambda in all; the zero mode (the free spin) and the bearing persist.
void split_modes(const StabilityResult& s, Reduction& r) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(s.jacobian);
  const Eigen::VectorXcd lambda = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  const Eigen::MatrixXcd V_inv = V.inverse();
  Eigen::VectorXcd gain = Eigen::VectorXcd::Zero(lambda.size()), keep = Eigen::VectorXcd::Zero(lambda.size());
  keep[nearest(lambda, s.zero)] = 1.0;
  for (const Eigenvalue& b : s.modes.bearing) keep[nearest(lambda, b)] = 1.0;
  double slowest = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (keep[k] != 0.0) continue;
    gain[k] = -1.0 / lambda[k];
    slowest = std::min(slowest, std::abs(lambda[k].real()));
  }
  r.relaxation_time = 1.0 / slowest;
  r.offset = (V.topRows(2) * gain.asDiagonal() * V_inv).real();
  r.persisting = (V * keep.asDiagonal() * V_inv).real();
}

}  // namespace

Reduction analyse_reduction(const Model& model_in, const StationaryGeometry& geometry, const StateVector& y) {
  Model model = model_in;
  model.kind = ModelKind::full;
  Reduction r;
  r.spin = shell_spin(y);
  const double rotor_spin = model.top.has_rotor ? r.spin + y[idx::nu] : 0.0;
  const StationaryState st = stationary_state(model, geometry, r.spin);
  const StabilityResult s = stability_at(model, st, r.spin, rotor_spin);
  if (!s.exists) {
    r.reason = s.reason;
    return r;
  }
  if (!s.stable) {
    r.reason = "the sleeping state at spin " + format_number(r.spin) + " rad/s is unstable (largest Re = " +
               format_number(s.max_real) + " 1/s)";
    return r;
  }
  split_modes(s, r);
  r.coords = reduced_coordinates(model, st.f_hat);
  r.z_star = reduce(r.coords, stationary_state_vector(model, st, r.spin, Eigen::Vector2d::Zero(), rotor_spin));
  if (model.top.has_rotor && model.top.rotor.coupling > 0.0) {
    const Top& top = model.top;
    const double spin_rate = top.rotor.coupling * y[idx::nu] / shell_axial_inertia(top);
    const double drag_time = 1.0 / (top.rotor.coupling * (1.0 / top.rotor.inertia_axial + 1.0 / shell_axial_inertia(top)));
    const double lag = st.velocity.norm() * std::abs(spin_rate / r.spin) * r.relaxation_time * drag_time;
    if (!(lag <= model.automatic.position_tolerance)) {
      r.reason = "the bearing drags the spin (" + format_number(spin_rate) + " rad/s^2) too fast for the sleeping " +
                 "state to follow: predicted lag " + format_number(lag) + " m over model.auto_tolerance";
      return r;
    }
  }
  r.valid = true;
  return r;
}

bool reduction_applies(const Reduction& r, const StateVector& y) {
  return std::abs(shell_spin(y) - r.spin) <= kReanalysedSpin * std::abs(r.spin);
}

Eigen::Vector2d remaining_offset(const Reduction& r, const StateVector& y) {
  return r.offset * (reduce(r.coords, y) - r.z_star);
}

Handover handover(const Model& model_in, const StationaryGeometry& geometry, const Reduction& r,
                  const StateVector& y) {
  Model model = model_in;
  model.kind = ModelKind::adiabatic;
  const Eigen::VectorXd dz = reduce(r.coords, y) - r.z_star;
  const Eigen::VectorXd z_end = r.z_star + r.persisting * dz;  // where the decaying modes leave the state
  Handover h;
  h.offset = r.offset * dz;
  h.y = y;
  set_position(h.y, position(y) + h.offset);
  const StateVector y_end = expand(r.coords, z_end);
  const double spin = angular_velocity(y_end).dot(r.coords.f_star);
  set_figure_axis(h.y, r.coords.f_star);
  set_angular_velocity(h.y, spin * r.coords.f_star);
  if (r.coords.rotor) h.y[idx::nu] = z_end[7];
  project_to_stationary(model, geometry, h.y);
  return h;
}

}  // namespace top_sim
