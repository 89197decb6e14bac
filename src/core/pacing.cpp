#include "top_sim/pacing.hpp"

#include <algorithm>
#include <limits>

namespace top_sim {

Pacer::Pacer(double real_time_factor, double rate, double wall, double sim, const PacingOptions& options)
    : factor_(std::max(0.0, real_time_factor)),
      rate_(rate > 0.0 ? rate : 1.0),
      options_(options),
      anchor_wall_(wall),
      anchor_sim_(sim) {}

Pacer::Tick Pacer::plan(double wall, double sim) {
  Tick tick;
  tick.budget = budget();
  if (factor_ <= 0.0) {
    tick.target = sim + options_.fast_horizon;
    return tick;
  }
  double target = anchor_sim_ + factor_ * (wall - anchor_wall_);
  if ((target - sim) / factor_ > options_.max_debt) {
    drop_debt(wall, sim, target);
    // Re-anchored one period back: this tick asks for one period of simulated time, the next for two, ...
    anchor_wall_ = wall - 1.0 / rate_;
    anchor_sim_ = sim;
    target = sim + factor_ / rate_;
    tick.dropped_debt = true;
  }
  tick.target = std::max(target, sim);
  return tick;
}

double Pacer::due(double wall, double sample_sim) {
  if (factor_ <= 0.0) return wall;
  double at = anchor_wall_ + (sample_sim - anchor_sim_) / factor_;
  if (wall - at > options_.max_debt) {
    drop_debt(wall, sample_sim, sample_sim + factor_ * (wall - at));
    anchor_wall_ = wall;
    anchor_sim_ = sample_sim;
    at = wall;
  }
  return at;
}

void Pacer::drop_debt(double wall, double sim, double target) {
  (void)wall;
  ++drops_;
  dropped_sim_ += std::max(0.0, target - sim);
}

void Pacer::record(double wall, double sim, bool running) {
  if (!running) {  // stopped (paused, faulted): nothing to measure; the window restarts here when it runs again
    window_.clear();
    window_.emplace_back(wall, sim);
    read_window_ends();
    achieved_ = 0.0;
    behind_ = false;
    return;
  }
  if (!window_.empty() && wall < ends_.newest_wall) window_.clear();  // the wall clock went back: start over
  // One point per window / kWindowPoints of wall time, not one per tick; the window spans 1 to 1 + 1/kWindowPoints
  // of its length. A tick reads only ends_ (next to the clock's anchor): with a thousand tops at 200 Hz the points
  // themselves are never in the cache (reading them was 3 % of the node).
  if (window_.empty() || wall - ends_.newest_wall >= options_.window / kWindowPoints) {
    window_.emplace_back(wall, sim);
    read_window_ends();
  }
  while (window_.size() > 1 && wall - ends_.second_wall >= options_.window) {
    window_.pop_front();
    read_window_ends();
  }
  const double dw = wall - ends_.oldest_wall;
  achieved_ = dw > 0.0 ? (sim - ends_.oldest_sim) / dw : 0.0;
  if (factor_ <= 0.0) {
    behind_ = false;
    return;
  }
  if (dw < options_.min_window) return;  // too short a window to judge: keep the state
  if (!behind_ && achieved_ < options_.behind_enter * factor_)
    behind_ = true;
  else if (behind_ && achieved_ >= options_.behind_leave * factor_)
    behind_ = false;
}

void Pacer::read_window_ends() {
  ends_ = WindowEnds();
  if (window_.empty()) return;
  ends_.oldest_wall = window_.front().first;
  ends_.oldest_sim = window_.front().second;
  ends_.newest_wall = window_.back().first;
  if (window_.size() > 1) ends_.second_wall = window_[1].first;
}

void Pacer::reanchor(double wall, double sim, bool clear_window) {
  anchor_wall_ = wall;
  anchor_sim_ = sim;
  if (clear_window) {
    window_.clear();
    read_window_ends();
    achieved_ = 0.0;
    behind_ = false;
  }
}

void Pacer::set_real_time_factor(double real_time_factor, double wall, double sim) {
  factor_ = std::max(0.0, real_time_factor);
  reanchor(wall, sim, true);
}

void Pacer::set_rate(double rate) {
  if (rate > 0.0) rate_ = rate;
}

double Pacer::debt(double wall, double sim) const {
  if (factor_ <= 0.0) return 0.0;
  return std::max(0.0, (anchor_sim_ + factor_ * (wall - anchor_wall_) - sim) / factor_);
}

}  // namespace top_sim
