// Regime classification (physics.md section 8).
#include "top_sim/regime.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "shape_motion.hpp"

#include "top_sim/contact.hpp"

namespace top_sim {

const char* to_string(Regime r) {
  switch (r) {
    case Regime::nutating: return "nutating";
    case Regime::precessing: return "precessing";
    case Regime::sleeping: return "sleeping";
    case Regime::sliding: return "sliding";
    case Regime::contact_fault: return "contact_fault";
    case Regime::upright: return "upright";
    case Regime::inverting: return "inverting";
    case Regime::inverted: return "inverted";
    case Regime::tumbling: return "tumbling";
    case Regime::rolling: return "rolling";
    case Regime::on_crown: return "on_crown";
    case Regime::on_stem: return "on_stem";
    case Regime::at_rest: return "at_rest";
    case Regime::lying_flat: return "lying_flat";
    case Regime::fallen: return "fallen";
  }
  return "?";
}

Regime end_regime(EndState state) {
  switch (state) {
    case EndState::at_rest: return Regime::at_rest;
    case EndState::lying_flat: return Regime::lying_flat;
    case EndState::fallen: return Regime::fallen;
    case EndState::none: break;
  }
  return Regime::nutating;
}

RegimeIndicators regime_indicators(const Model& model, ContactMode mode, const StateVector& y, const Dynamics& dyn,
                                   const StationaryState& st) {
  RegimeIndicators ind;
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d f_dot = w.cross(f_hat);

  // Near zero shell spin the angle of omega is ill-defined: a gyrostat uses L_total's direction (section 6).
  Eigen::Vector3d a, a_dot;
  double c, c_dot;
  if (top.has_rotor) {
    const double J = top.rotor.inertia_axial, I_fs = top.inertia_axial - J, I_d = top.inertia_transverse;
    const double w_f = w.dot(f_hat);
    const Eigen::Vector3d L = I_d * w + ((I_fs - I_d) * w_f + J * (w_f + y[idx::nu])) * f_hat;
    const Eigen::Vector3d rho = -(top.tip_radius * Eigen::Vector3d::UnitZ() + top.com_offset * f_hat);
    const Eigen::Vector3d L_dot = rho.cross(dyn.contact_force);
    a = L.cross(f_hat);
    a_dot = L_dot.cross(f_hat) + L.cross(f_dot);
    c = L.dot(f_hat);
    c_dot = L_dot.dot(f_hat) + L.dot(f_dot);
  } else {
    a = w.cross(f_hat);
    a_dot = dyn.omega_dot.cross(f_hat) + w.cross(f_dot);
    c = w.dot(f_hat);
    c_dot = dyn.omega_dot.dot(f_hat) + w.dot(f_dot);
  }
  const double an = a.norm(), cn = std::abs(c);
  ind.nutation_angle = std::atan2(an, cn);
  const double an_dot = an > 0.0 ? a.dot(a_dot) / an : a_dot.norm();
  const double cn_dot = c >= 0.0 ? c_dot : -c_dot;
  const double denom = an * an + cn * cn;
  ind.nutation_rate = denom > 0.0 ? (cn * an_dot - an * cn_dot) / denom : 0.0;

  // safe_norm (contact.hpp): a finite a_cm of 1e161 m/s^2 (an air drag of 1e163 N s/m) squared to inf in norm().
  ind.acceleration = safe_norm(dyn.a_cm);
  ind.speed = safe_norm(velocity3(y) + w.cross(top.com_offset * f_hat));

  ind.runaway = !st.exists || (st.slip_unstable >= 0.0 && dyn.contact.slip > st.slip_unstable);
  ind.tippe = top.com_offset < 0.0;
  ind.tilt = std::acos(std::max(-1.0, std::min(1.0, f_hat.z())));
  ind.slip = dyn.contact.slip;
  ind.shape_body = has_shapes(model);
  if (ind.shape_body) {
    ind.touching = touching_shapes(model, mode);
    for (std::size_t k = 0; k < model.shapes.count; ++k)
      if (model.shapes.shape[k].kind == ShapeKind::rim) ind.touching_rims |= ind.touching & (1u << k);
  }
  return ind;
}

namespace {

// A tumbling top stays so until its slip is 5 times the threshold: over one nutation the slip swings by a factor
// of about 5 (tippe_top_tumbling.yaml, 3-5 s), and the regime must not flicker with it.
Regime tippe_regime(const RegimeIndicators& ind, Regime previous) {
  if (ind.tilt < kTippeEndTilt) return Regime::upright;
  if (ind.tilt > M_PI - kTippeEndTilt) return Regime::inverted;
  const double k = previous == Regime::tumbling ? 5.0 : 1.0;
  return ind.slip < k * kTippeGlidingSlip ? Regime::tumbling : Regime::inverting;
}

// What a body of shapes touches with, when that decides the word (none: on its first sphere, or in flight, where the
// tip sphere's words apply).
std::optional<Regime> shape_regime(const RegimeIndicators& ind) {
  if (!ind.shape_body || ind.touching == 0) return std::nullopt;
  if ((ind.touching & (ind.touching - 1)) != 0) return Regime::rolling;  // two shapes: it rolls on them as a cone
  if (ind.touching_rims != 0) return ind.touching == 1u ? Regime::rolling : Regime::on_crown;  // a disc on its edge
  if (ind.touching != 1u) return Regime::on_stem;
  return std::nullopt;
}

}  // namespace

Regime classify(const RegimeThresholds& th, const RegimeIndicators& ind, bool fault, Regime previous) {
  if (fault) return Regime::contact_fault;
  if (const std::optional<Regime> touching = shape_regime(ind)) return *touching;
  if (ind.tippe) return tippe_regime(ind, previous);
  // A sliding top keeps a steady omega-f_hat offset from the friction torque: sliding outranks nutation.
  if (ind.runaway) return Regime::sliding;
  if (ind.nutation_angle > th.nutation_angle || std::abs(ind.nutation_rate) > th.nutation_rate)
    return Regime::nutating;
  const double k = previous == Regime::sleeping ? 2.0 : 1.0;
  const bool straight =
      ind.acceleration <= k * th.sleep_acceleration || ind.acceleration <= k * th.sleep_turn_rate * ind.speed;
  return straight ? Regime::sleeping : Regime::precessing;
}

}  // namespace top_sim
