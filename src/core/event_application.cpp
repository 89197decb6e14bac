// Applying a located event: a mode switch (stick, slip, lift-off), an impact at touchdown, or a fault (physics.md
// sections 8 and 9); the contact mode's history and the Zeno guard.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "simulator_impl.hpp"
#include "top_sim/simulator.hpp"  // its public constants: the mode switches kept
#include "top_sim/format.hpp"
#include "impact.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {

constexpr int kMaxInstantSwitches = 100;  // mode switches at one instant before the Zeno guard stops the run
// Event clustering: more than this many switches, each within kClusterGap of the one before, stop the run with a
// named fault (contacts chattering faster than any motion they stand for) instead of stepping ever shorter.
constexpr int kMaxClusteredSwitches = 1000;
constexpr double kClusterGap = 1e-6;  // s

std::string impact_painleve_message(double t, double denominator) {
  std::ostringstream os;
  os << "t = " << format_number(t) << " s: ";
  os << "Painleve at impact: the sliding impulse has no admissible normal part (n . K (n - mu_i t_hat) = "
     << denominator << " <= 0); reduce the friction";
  return os.str();
}

}  // namespace

// The event at the committed state (margins m there): the state after it is committed and the stepper restarted.
void SimulatorImpl::apply_event(Event event, const ModeMargins& m) {
  StateVector y = y_;
  switch (event) {
    case Event::painleve:
      fail(ContactFault::painleve, describe(ContactFault::painleve, m.painleve, t_));
      return;
    case Event::end:  // a rim lying flat, a body at rest on two shapes, a top fallen past max_tilt
      end(tilt_end_state(model_), m.end);
      return;
    case Event::transfer:
      if (has_shapes(model_) && two_touching(model_.shapes)) {
        if (!pair_transfer(y)) return;
        break;
      }
      if (mode_ == ContactMode::slipping) {
        const double e0 = mechanical_energy(model_, y);
        if (!stick_inside_cone(model_, y)) {  // slip on, the stick disarmed until its margin has been positive
          restart(y_, t_, false);
          transfer_armed_ = false;
          return;
        }
        const double loss = e0 - mechanical_energy(model_, y);
        y[idx::w_diss] += loss;
        switch_mode(ContactMode::rolling, ModeSwitchKind::stick, -loss);
      } else {
        switch_mode(ContactMode::slipping, ModeSwitchKind::slip);  // starts with v_t = 0
      }
      break;
    case Event::lift_off:
      if (has_shapes(model_) && two_touching(model_.shapes)) {  // one of two lets go; the other stays
        let_go_of_one(y);
        break;
      }
      y[idx::gap] = y[idx::gap_rate] = 0.0;
      switch_mode(ContactMode::flight, ModeSwitchKind::lift_off);
      break;
    case Event::second_touchdown:
      second_touchdown(y);
      break;
    case Event::touchdown:
      touchdown(y);
      break;
    default:
      return;
  }
  if (!stopped()) restart(y, t_, false); else commit(y, t_);
}

// The touchdown after a flight: the impact at the shape that reached the plane, then the closing rule.
void SimulatorImpl::touchdown(StateVector& y) {
  if (has_shapes(model_)) retouch(model_, y, lowest_shape(model_, y));  // the shape that reached the plane
  y[idx::gap] = 0.0;
  const double e0 = mechanical_energy(model_, y);
  const ImpactResult impact = apply_impact(model_, y);
  if (impact.painleve) {
    fail(ContactFault::painleve, impact_painleve_message(t_, impact.denominator));
    return;
  }
  ContactMode next = ContactMode::flight;  // a bounce flies again
  if (impact.plastic) next = close_contact(model_, y).mode;  // Painleve: slipping, reported by the restart
  const double loss = e0 - mechanical_energy(model_, y);  // an impact never raises E: the loss is booked
  y[idx::w_diss] += loss;
  switch_mode(next, ModeSwitchKind::touchdown, -loss);
}

// A shape not touching reaches the plane while one touches (apply_second_touchdown): afterwards both touch and
// slip, or the new one alone touches (closing rule), or it bounced into a flight. The impact's loss is booked.
void SimulatorImpl::second_touchdown(StateVector& y) {
  std::size_t j;
  free_shape_gap(model_, y, j);
  if (two_touching(model_.shapes)) {  // scene.cpp refuses a body of more than two shapes: never reached
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t_) + " (a third shape touched)");
    return;
  }
  const double e0 = mechanical_energy(model_, y);
  const SecondTouchdown impact = apply_second_touchdown(model_, y, j);
  if (impact.painleve) {
    const std::string shared = "t = " + format_number(t_) + " s: Painleve at the impact of top.shapes[" +
                               std::to_string(j) + "] with top.shapes[" + std::to_string(model_.shapes.touching) +
                               "] touching: no plastic impulse pair with both normal parts >= 0 (" +
                               format_number(impact.denominator) + "); reduce the friction";
    fail(ContactFault::painleve, impact.both_tried ? shared : impact_painleve_message(t_, impact.denominator));
    return;
  }
  ContactMode next = ContactMode::slipping;
  if (impact.bounced) next = ContactMode::flight;
  else if (!impact.both) next = close_contact(model_, y).mode;
  const double loss = e0 - mechanical_energy(model_, y);
  y[idx::w_diss] += loss;
  // A shape's impact that throws the body off the plane is, for the body in contact, a lift-off.
  switch_mode(next, next == ContactMode::flight ? ModeSwitchKind::lift_off : ModeSwitchKind::touchdown, -loss);
  if (impact.both) settle_pair(y);
}

// One contact of two sticks or slips (section 9 at each): the contact whose margin crossed. A stick takes the pair's
// stick impulse and holds only if the pair then holds that contact inside its cone (else it slips on, the stick
// disarmed); the other contact may then hold too. The mode is rolling while both stick. False when nothing changed
// (the stepper restarted).
bool SimulatorImpl::pair_transfer(StateVector& y) {
  const TwoShapeMotion m = touching_pair_motion(model_, y);
  const int k = pair_contact_margin(model_, y, m, 0) <= pair_contact_margin(model_, y, m, 1) ? 0 : 1;
  if (model_.shapes.stuck[k]) {
    model_.shapes.stuck[k] = false;
    switch_mode(pair_mode(), ModeSwitchKind::slip);
    return true;
  }
  if (!stick_pair_contact(y, k)) {
    restart(y_, t_, false);
    transfer_armed_ = false;
    return false;
  }
  stick_pair_contacts(y);
  return true;
}

ContactMode SimulatorImpl::pair_mode() const {
  return model_.shapes.stuck[0] && model_.shapes.stuck[1] ? ContactMode::rolling : ContactMode::slipping;
}

bool SimulatorImpl::stick_pair_contact(StateVector& y, int k) {
  const double e0 = mechanical_energy(model_, y);
  StateVector stuck = y;
  apply_pair_stick_impulse(model_, stuck, k);
  model_.shapes.stuck[k] = true;
  if (!(pair_contact_margin(model_, stuck, touching_pair_motion(model_, stuck), k) > 0.0)) {
    model_.shapes.stuck[k] = false;
    return false;
  }
  y = stuck;
  const double loss = e0 - mechanical_energy(model_, y);
  y[idx::w_diss] += loss;
  switch_mode(pair_mode(), ModeSwitchKind::stick, -loss);
  return true;
}

// Section 9's closing rule at two contacts: each slipping contact whose margin is already down (slow enough, and held
// inside its cone with it stuck) sticks now; its margin would never fire, having not been positive.
void SimulatorImpl::stick_pair_contacts(StateVector& y) {
  if (!(static_friction(model_) > 0.0) || model_.finite_contact.has_patch()) return;
  for (int k = 0; k < 2; ++k)
    if (!model_.shapes.stuck[k] && pair_contact_margin(model_, y, touching_pair_motion(model_, y), k) <= 0.0)
      stick_pair_contact(y, k);
}

// Two shapes touching: the one whose normal force is the smaller lets go when it is negative; the other closes
// (closing rule: it may stick, or fly when its own normal force is negative too). The state's gap becomes the
// remaining shape's (its drift from 0, the constraint's integration error, is booked with the energy).
void SimulatorImpl::let_go_of_one(StateVector& y) {
  const TwoShapeMotion m = touching_pair_motion(model_, y);
  const double e0 = mechanical_energy(model_, y);
  if (m.normal_force[0] < m.normal_force[1]) retouch(model_, y, model_.shapes.second);
  model_.shapes.second = kNoShape;
  model_.shapes.stuck = {false, false};
  const ClosingResult closed = close_contact(model_, y);
  const double change = mechanical_energy(model_, y) - e0;
  y[idx::w_diss] -= change;
  switch_mode(closed.mode, ModeSwitchKind::lift_off, change);
}

// After a second touchdown: a pair whose forces pull one shape onto the plane is no contact pair; that shape lets
// go at once; else its slow contacts may stick (stick_pair_contacts).
void SimulatorImpl::settle_pair(StateVector& y) {
  const TwoShapeMotion m = touching_pair_motion(model_, y);
  if (m.normal_force[0] < 0.0 || m.normal_force[1] < 0.0)
    let_go_of_one(y);
  else
    stick_pair_contacts(y);
}

void SimulatorImpl::switch_mode(ContactMode mode, ModeSwitchKind kind, double energy_change) {
  mode_seconds_[static_cast<int>(mode_)] += t_ - mode_since_;
  mode_since_ = t_;
  if (switches_.size() < Simulator::kMaxPendingSwitches) switches_.push_back({t_, kind, mode_, mode, energy_change});
  ++switch_count_;
  mode_ = mode;
  instant_switches_ = t_ - last_switch_t_ > 1e-12 * std::max(1.0, std::abs(t_)) ? 0 : instant_switches_ + 1;
  clustered_switches_ = t_ - last_switch_t_ > kClusterGap ? 0 : clustered_switches_ + 1;
  last_switch_t_ = t_;
  if (clustered_switches_ > kMaxClusteredSwitches) {
    std::ostringstream os;
    os << describe(ContactFault::numerical, 0.0, t_) << " (event clustering: " << clustered_switches_
       << " contact-mode switches each within " << kClusterGap << " s of the last, last " << to_string(kind)
       << " to " << to_string(mode) << ")";
    fail(ContactFault::numerical, os.str());
    return;
  }
  if (instant_switches_ > kMaxInstantSwitches) {
    std::ostringstream os;
    os << describe(ContactFault::numerical, 0.0, t_) << " (" << instant_switches_
       << " contact-mode switches without time advancing, last " << to_string(kind) << " to " << to_string(mode)
       << ")";
    fail(ContactFault::numerical, os.str());
  }
}

// The closed-form flight (flight.hpp) where its dynamics is gravity and no torque, else the numeric stepper; a
// fixed-step method is chosen to see that method's own error, so its flights are stepped too.
void SimulatorImpl::select_stepper() {
  const bool closed =
      mode_ == ContactMode::flight && flight_in_closed_form(model_) && is_adaptive(scene_.integrator.method);
  if (closed == closed_flight_) return;
  std::swap(stepper_, parked_);
  closed_flight_ = closed;
}

std::array<double, kContactModeCount> SimulatorImpl::mode_seconds() const {
  std::array<double, kContactModeCount> s = mode_seconds_;
  s[static_cast<int>(mode_)] += t_ - mode_since_;
  return s;
}

std::vector<ModeSwitch> SimulatorImpl::take_mode_switches() {
  std::vector<ModeSwitch> out;
  out.swap(switches_);
  return out;
}

}  // namespace top_sim
