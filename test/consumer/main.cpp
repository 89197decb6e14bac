// Loads the installed default scene by its data path and runs it for 1 s: prints the final phi and time.
#include <cstdio>

#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

int main() {
  const std::string config = top_sim::default_config_dir();
  if (config.empty()) {
    std::fprintf(stderr, "consumer: no data directory found next to the installed core\n");
    return 1;
  }
  top_sim::Simulator sim(top_sim::load_scene(config + "/scenes/default.yaml"));
  sim.advance_to(1.0);
  const top_sim::Snapshot s = sim.snapshot();
  std::printf("config %s\nt %.6f energy %.9g\n", config.c_str(), s.t, s.energy);
  return s.t == 1.0 && sim.fault() == top_sim::ContactFault::none ? 0 : 1;
}
