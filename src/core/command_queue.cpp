// The command queue and the scene's scripted events: commands from any thread, applied at a step boundary.
#include <limits>

#include "simulator_impl.hpp"
#include "shape_motion.hpp"

namespace top_sim {

std::string SimulatorImpl::submit(const Command& command) {
  std::lock_guard<std::mutex> lock(pending_mutex_);  // the owner writes model_ only under it
  if (!stopped_refusal_.empty()) return stopped_refusal_;
  const std::string error = validate(command, model_);
  if (!error.empty()) return error;
  pending_.push_back(command);
  has_pending_.store(true, std::memory_order_release);
  return "";
}

void SimulatorImpl::schedule_next_event() {
  next_event_t_ = next_event_ < scene_.events.size() ? t_origin_ + scene_.events[next_event_].t
                                                     : std::numeric_limits<double>::infinity();
}

// The queued commands, then the scene events due, applied together; the stepper restarts at the changed state.
void SimulatorImpl::apply_pending() {
  // Most calls find nothing: no lock then (an uncontended lock still costs a cold cache line per top and call).
  if (!scene_event_due() && !has_pending_.load(std::memory_order_acquire)) return;
  StateVector y = y_;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    std::vector<Command> due;
    due.swap(pending_);
    has_pending_.store(false, std::memory_order_relaxed);
    while (scene_event_due()) {
      due.push_back(scene_.events[next_event_++].command);
      schedule_next_event();
    }
    if (due.empty()) return;
    // Under auto every command and event lands in the full model.
    if (model_.automatic.enabled && model_.kind != ModelKind::full) resume_full(t_);
    reduction_ = Reduction{};
    for (const Command& c : due) apply_command(c, model_, y);  // model_ under the lock: submit() reads it
  }
  stationary_geometry_ = stationary_geometry(model_);  // the inclination or the law may have changed
  reclose_contact(y);
  restart(y, t_, true);
}

// A contact that a command changed (spin, friction, inclination) may no longer hold in its mode: the closing rule
// decides again (a flight stays a flight).
void SimulatorImpl::reclose_contact(StateVector& y) {
  if (mode_ == ContactMode::flight || !has_contact_modes(model_)) return;
  // Two contacts, one now pulling (N_k < 0: a spin flung the body up on it): it lets go at once, as after a second
  // touchdown. Its lift-off event could not: restart() arms the lift margin only once it has been positive.
  if (has_shapes(model_) && two_touching(model_.shapes)) {
    const TwoShapeMotion m = touching_pair_motion(model_, y);
    if (m.normal_force[0] < 0.0 || m.normal_force[1] < 0.0) return let_go_of_one(y);
  }
  const ContactMode before = mode_;
  const double e0 = mechanical_energy(model_, y);
  const ClosingResult c = close_contact(model_, y);
  const double loss = e0 - mechanical_energy(model_, y);  // the stick impulse's loss, if any
  y[idx::w_diss] += loss;
  if (c.mode != before) {  // a Painleve state comes back as slipping: restart() reports it
    const ModeSwitchKind kind = c.mode == ContactMode::flight  ? ModeSwitchKind::lift_off
                                : c.mode == ContactMode::rolling ? ModeSwitchKind::stick
                                                                 : ModeSwitchKind::slip;
    switch_mode(c.mode, kind, -loss);
  }
}

}  // namespace top_sim
