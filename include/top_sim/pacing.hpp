// Real-time pacing of a simulation against the wall clock, shared by top_sim_node and `top_sim_run --lcm`
// (docs/ros.md, "Time"). ROS-free and clock-free: every call takes the wall time and the simulated time, so tests
// drive it with a fake clock.
//
// The rule, for a requested real-time factor f > 0 and a loop at `rate` ticks per wall second:
//   - the simulated target of a tick is anchor_sim + f (wall - anchor_wall);
//   - the physics of one tick may spend at most budget_fraction / rate wall seconds (default 50 % of the period),
//     so the loop keeps its rate and answers its callbacks whatever the scene costs;
//   - when the simulation trails its target by more than max_debt wall seconds (default 0.5 s; physics too slow
//     or the process starved), the debt is dropped: the clock re-anchors at (wall, sim) and the target becomes
//     one period ahead, so it never bursts to catch up (dropped_sim_seconds() counts what was given up);
//   - the achieved factor is (sim change) / (wall change) over a sliding window of about one wall second;
//   - behind() turns true when, over a window of at least min_window wall seconds, the achieved factor is below
//     behind_enter (95 %) of the requested one, and false again once it is back to at least behind_leave (98 %)
//     (hysteresis: no flapping around the threshold).
// With f = 0 (as fast as possible) a tick's target is far ahead (sim + fast_horizon) and only the budget limits
// it; there is no debt and never `behind`.
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <utility>

namespace top_sim {

struct PacingOptions {
  double budget_fraction = 0.5;  // physics budget per tick, as a fraction of the period 1 / rate
  double max_debt = 0.5;         // wall seconds of lag after which the debt is dropped (re-anchor)
  double window = 1.0;           // wall seconds of the achieved-factor window
  double min_window = 0.5;       // wall seconds the window must span before behind() may change
  double behind_enter = 0.95;    // behind when achieved < behind_enter * requested
  double behind_leave = 0.98;    // back to OK when achieved >= behind_leave * requested
  double fast_horizon = 1.0e3;   // f = 0: simulated seconds a tick may at most advance
};

class Pacer {
 public:
  // real_time_factor >= 0 (0 = as fast as possible), rate > 0 [Hz]; anchored at (wall, sim).
  Pacer(double real_time_factor, double rate, double wall, double sim, const PacingOptions& options = {});

  // One tick of a time-driven loop (the node): the simulated time to advance to and the physics budget.
  struct Tick {
    double target = 0.0;        // simulated time to advance to
    double budget = 0.0;        // wall seconds the physics may spend on it
    bool dropped_debt = false;  // this tick re-anchored (more than max_debt behind)
  };
  Tick plan(double wall, double sim);

  // Sample-driven loop (top_sim_run --lcm): the wall instant at which the sample at simulated time `sample_sim`
  // is due. A sample due more than max_debt ago re-anchors (due now) instead of being rushed out.
  double due(double wall, double sample_sim);

  // After the physics (or after sending a sample): feeds the achieved-factor window and the behind state.
  // running = false (paused, stopped by a fault): the achieved factor is 0, behind() is false, and the window
  // restarts there, so the seconds spent stopped never count against the run that follows (a reset after a fault).
  void record(double wall, double sim, bool running = true);

  // Re-anchors at (wall, sim): after pause, resume, reset or a jump. clear_window also forgets the achieved factor
  // (pause and resume do; a reset, whose time keeps running forward, does not need to).
  void reanchor(double wall, double sim, bool clear_window = true);

  void set_real_time_factor(double real_time_factor, double wall, double sim);  // re-anchors, clears the window
  void set_rate(double rate);

  double real_time_factor() const { return factor_; }
  double rate() const { return rate_; }
  double budget() const { return options_.budget_fraction / rate_; }
  double achieved_factor() const { return achieved_; }
  bool behind() const { return behind_; }
  // Wall seconds the simulation trails its target at (wall, sim); 0 with f = 0.
  double debt(double wall, double sim) const;
  std::uint64_t debt_drops() const { return drops_; }
  double dropped_sim_seconds() const { return dropped_sim_; }
  const PacingOptions& options() const { return options_; }

 private:
  void drop_debt(double wall, double sim, double target);
  void read_window_ends();  // after every change of window_

  static constexpr double kWindowPoints = 16.0;  // points of the achieved-factor window per window length
  struct WindowEnds {  // what a tick reads of window_, copied out of it when it changes
    double oldest_wall = 0.0, oldest_sim = 0.0;
    double newest_wall = 0.0;
    double second_wall = std::numeric_limits<double>::infinity();  // the point after the oldest; none: infinity
  };

  double factor_, rate_;
  PacingOptions options_;
  double anchor_wall_, anchor_sim_;
  WindowEnds ends_;  // next to the anchor that plan() has just read: a tick touches no other memory of the Pacer
  double achieved_ = 0.0;
  bool behind_ = false;
  std::deque<std::pair<double, double>> window_;  // (wall, sim), at least window / kWindowPoints apart
  std::uint64_t drops_ = 0;
  double dropped_sim_ = 0.0;
};

}  // namespace top_sim
