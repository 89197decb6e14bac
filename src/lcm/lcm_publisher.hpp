// LCM adapter: maps a core Snapshot onto top_sim.top_state_t and publishes it (not part of top_sim_core).
#pragma once

#include <memory>
#include <string>

#include "top_sim/snapshot.hpp"

namespace lcm { class LCM; }
namespace top_sim { class top_state_t; }

namespace top_sim_lcm {

// What the streaming adapter adds to a snapshot (TopState's real_time_factor, requested_real_time_factor, paused,
// and friction_law: the model's, which the snapshot does not carry).
struct Pacing {
  double achieved = 0.0;   // simulated seconds per wall second
  double requested = 1.0;  // 0 = as fast as possible
  bool paused = false;
  const char* friction_law = "";  // the law in force (top_sim::to_string of the model's)
};

// Field-by-field copy of the snapshot and the pacing.
void to_lcm(const top_sim::Snapshot& s, const Pacing& pacing, top_sim::top_state_t& out);

// Opens one LCM instance; when it cannot (e.g. no multicast route) ok() is false and error() says why.
class Publisher {
 public:
  Publisher(const std::string& url, const std::string& channel);
  ~Publisher();
  bool ok() const { return ok_; }
  const std::string& error() const { return error_; }
  const std::string& channel() const { return channel_; }
  // Returns false when the send failed (nothing else happens: the caller keeps running).
  bool publish(const top_sim::Snapshot& s, const Pacing& pacing);

 private:
  std::unique_ptr<lcm::LCM> lcm_;
  std::string channel_;
  bool ok_ = false;
  std::string error_;
};

}  // namespace top_sim_lcm
