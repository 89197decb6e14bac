// peer_mujoco --pivot: the pivoting upright top in top_sim and MuJoCo (condim 4) against the closed form.
#pragma once

#include <string>

namespace peer {

// Prints the table (markdown) and writes `csv` if not empty; `config_dir` holds tops/ (the top is aluminium).
int pivot(const std::string& config_dir, int reps, const std::string& csv);

}  // namespace peer
