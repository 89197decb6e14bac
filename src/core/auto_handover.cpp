// model.kind auto (physics.md section 7.1): a sleeping top handed to the reduced model at a regime point, and back
// to the full model where the reduction no longer holds or a command arrives (command_queue.cpp).
#include "simulator_impl.hpp"

#include <algorithm>
#include <cmath>

namespace top_sim {

// Hand over at this regime point when the reduction is valid at its spin and the decaying modes would still move
// the contact point by at most model.auto_tolerance.
void SimulatorImpl::consider_handover(double t, const StateVector& y) {
  if (!reduction_applies(reduction_, y)) reduction_ = analyse_reduction(model_, stationary_geometry_, y);
  if (!reduction_.valid || !(remaining_offset(reduction_, y).norm() <= model_.automatic.position_tolerance)) return;
  const Handover h = handover(model_, stationary_geometry_, reduction_, y);
  handover_due_ = true;
  handover_.t = t;
  handover_.y = h.y;
  handover_.energy_loss = mechanical_energy(model_, y) - mechanical_energy(model_, h.y);
}

// The handover found by the regime clock: the state and time go there, the reduced model takes over.
bool SimulatorImpl::take_handover() {
  if (!handover_due_) return false;
  handover_due_ = false;
  StateVector y = handover_.y;
  y[idx::w_diss] += handover_.energy_loss;  // the decaying modes' energy, as their friction would have taken it
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    model_.kind = ModelKind::adiabatic;
  }
  ++handovers_;
  reduced_since_ = handover_.t;
  restart(y, handover_.t, false);
  return true;
}

// The reduced model has no events. Under auto its regime points are counted; with a spin moved by the bearing, a
// patch or air, the reduction is analysed again at each 1 % of the spin's change over the step (its dense output:
// a patch spins down at a constant rate, so one long step can cross a wake-up), and where it is no longer valid the
// full model resumes there.
bool SimulatorImpl::scan_reduced(double t_end, const StateVector& y1) {
  const double t0 = scanned_;
  scanned_ = t_end;
  if (!model_.automatic.enabled) {
    run_cadence(t_end);
    return !stopped();
  }
  if (reduction_applies(reduction_, y1)) {
    skip_cadence(t_end);
    return true;
  }
  const double change = std::abs(shell_spin(y1) - reduction_.spin) / (kReanalysedSpin * std::abs(reduction_.spin));
  const int pieces = static_cast<int>(std::min(std::ceil(std::isfinite(change) ? change : 1.0), 1000.0));
  StateVector yk = y1;
  double tk = t_end;
  for (int k = 1; k <= pieces; ++k) {
    tk = k == pieces ? t_end : t0 + (t_end - t0) * k / pieces;
    if (k == pieces) yk = y1; else stepper_->state_at(tk, yk);
    if (reduction_applies(reduction_, yk)) continue;
    reduction_ = analyse_reduction(model_, stationary_geometry_, yk);
    if (!reduction_.valid) break;
  }
  skip_cadence(tk);
  if (reduction_.valid) return true;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    resume_full(tk);
  }
  restart(yk, tk, false);
  return false;
}

// Called with pending_mutex_ held: it changes model_, which submit() reads from other threads.
void SimulatorImpl::resume_full(double t) {
  model_.kind = ModelKind::full;
  reduced_seconds_ += t - reduced_since_;
}

double SimulatorImpl::reduced_seconds() const {
  return reduced_seconds_ + (model_.automatic.enabled && model_.kind != ModelKind::full ? t_ - reduced_since_ : 0.0);
}

}  // namespace top_sim
