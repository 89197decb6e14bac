// The scene's method with rosenbrock4 across a stiff layer.
#include "dopri5.hpp"  // visible here so the calls through active() can be devirtualised (dopri5 is the usual primary)
#include "rosenbrock4.hpp"
#include "steppers.hpp"

namespace top_sim {

namespace {

// The model says where the state sits in a known stiff layer (the slip-onset layer of physics.md section 9); there
// rosenbrock4 takes over from whatever method the scene chose, and hands back once the state has left the layer.
// The hand-over happens at the start of the next step, so dense output always comes from the stepper that made
// the last step.
class LayeredStepper : public Stepper {
 public:
  LayeredStepper(std::unique_ptr<Stepper> primary, std::unique_ptr<Stepper> layer, StiffLayer in_layer)
      : primary_(std::move(primary)), layer_(std::move(layer)), in_layer_(std::move(in_layer)) {}

  void reset(const StateVector& y, double t) override {
    layer_active_ = in_layer_(y, false);
    active().reset(y, t);
    switch_pending_ = false;
  }

  void step(double t_limit) override {
    if (switch_pending_) {
      const StateVector y = active().state();
      const double t = active().time();
      layer_active_ = !layer_active_;
      active().reset(y, t);
      switch_pending_ = false;
    }
    Stepper& a = active();
    const StepperStats before = a.stats;
    a.step(t_limit);
    stats.steps += a.stats.steps - before.steps;
    stats.rejected += a.stats.rejected - before.rejected;
    stats.rhs_evaluations += a.stats.rhs_evaluations - before.rhs_evaluations;
    if (layer_active_) layer_steps_ += a.stats.steps - before.steps;
    switch_pending_ = in_layer_(a.state(), layer_active_) != layer_active_;
  }

  double time() const override { return active().time(); }
  double previous_time() const override { return active().previous_time(); }
  const StateVector& state() const override { return active().state(); }
  void state_at(double t, StateVector& y) const override { active().state_at(t, y); }
  double last_step_size() const override { return active().last_step_size(); }
  std::uint64_t layer_steps() const override { return layer_steps_; }
  bool state_was_last_rhs() const override { return active().state_was_last_rhs(); }

 private:
  Stepper& active() { return layer_active_ ? *layer_ : *primary_; }
  const Stepper& active() const { return layer_active_ ? *layer_ : *primary_; }

  std::unique_ptr<Stepper> primary_, layer_;
  StiffLayer in_layer_;
  bool layer_active_ = false, switch_pending_ = false;
  std::uint64_t layer_steps_ = 0;
};

}  // namespace

std::unique_ptr<Stepper> make_layered_stepper(std::unique_ptr<Stepper> primary, std::unique_ptr<Stepper> layer,
                                              StiffLayer in_layer) {
  return std::make_unique<LayeredStepper>(std::move(primary), std::move(layer), std::move(in_layer));
}
}  // namespace top_sim
