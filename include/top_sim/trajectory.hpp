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

}  // namespace top_sim
