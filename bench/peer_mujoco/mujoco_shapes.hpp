// peer_mujoco --tippe-top and --euler-disk (issue 34 item 4): MuJoCo's side of the several-shape bodies, measured
// so that top_sim's numbers can stand next to them (docs/performance/mujoco_shapes.md).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <string>

namespace peer {

struct ShapesOptions {
  int reps = 5;             // timed repetitions (the median is printed)
  bool check = false;       // the ctest: physics only, no timing
  bool print_mjcf = false;  // print the model and stop
  std::string csv;          // time courses for the plots (empty: none)
};

int tippe_top(const ShapesOptions& o);
int euler_disk(const ShapesOptions& o);

// One compiled model and its data (MuJoCo's C objects, freed together).
class MjInstance {
 public:
  explicit MjInstance(const std::string& xml);
  ~MjInstance();
  MjInstance(const MjInstance&) = delete;
  MjInstance& operator=(const MjInstance&) = delete;
  mjModel* m = nullptr;
  mjData* d = nullptr;
};

// The free body's orientation from qpos itself (after an RK4 mj_step, mjData's kinematics belong to its last stage).
Eigen::Quaterniond body_orientation(const mjData* d);
// The body's z axis in the world and its angle from the world vertical [rad].
Eigen::Vector3d body_axis(const mjData* d);
double tilt_from_vertical(const mjData* d);
// Whether MuJoCo's own collision detection (mj_fwdPosition), run on d's qpos in `scratch`, finds a contact between
// geoms g1 and g2 (d itself untouched: a probe in d would change the solver's warm start and so the run).
bool in_contact(const mjModel* m, const mjData* d, mjData* scratch, int g1, int g2);
// Prints a check line and returns ok.
bool expect(bool ok, const std::string& what);
std::string fmt(const char* f, double v);

}  // namespace peer
