// The columns of a sampled trajectory, defined once: top_sim_run's CSV and the Python module's NumPy arrays.
#pragma once

#include <vector>

#include "top_sim/snapshot.hpp"

namespace top_sim {

struct TrajectoryColumn {
  const char* name;
  const char* unit;                     // SI; "1" dimensionless, "code" for enumerations
  double (*value)(const Snapshot&);     // enumerations: their numeric code (TopState's constants)
  const char* (*text)(const Snapshot&); // enumerations: their name (the CSV writes it); nullptr otherwise
};

// In CSV order (docs/interfaces.md).
const std::vector<TrajectoryColumn>& trajectory_columns();

// The sample grid, one definition for top_sim_run and Python: sample k of a trajectory from t0 at `rate` samples per
// second is at t0 + k / rate (one rounding), for k = 0 .. last_sample_index; the last is at most `duration` after
// t0 (1e-12 relative slack, so that 1 s at 50 Hz ends on its 51st sample).
inline double sample_time(double t0, long k, double rate) { return t0 + static_cast<double>(k) / rate; }
long last_sample_index(double duration, double rate);

}  // namespace top_sim
