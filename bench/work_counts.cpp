// Deterministic work counts of whole runs (issue 21's guard, the table in docs/performance.md): steps, right-hand
// sides per step tried, sample analyses and stationary solves of an unread run, heap allocations per step. Counts,
// not times: the same on any machine for the same commit. test/core/counters_test.cpp asserts the limits; this
// prints what they are.   work_counts [CONFIG_DIR]   (markdown on stdout)
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "../src/core/counters.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

#include "counting_new.hpp"  // replaces the global operator new for this program

namespace {

struct Counts {
  double seconds = 0.0;
  top_sim::StepperStats stats;
  std::uint64_t switches = 0, analyses = 0, solves = 0, allocations = 0, first_read = 0, second_read = 0;
  std::string fault;
};

// The scene's whole run in one unread advance, counted from after the construction (which solves and allocates
// its set-up), then two reads of the final state.
Counts count_run(const std::string& path) {
  const top_sim::Scene scene = top_sim::load_scene(path);
  top_sim::WorkCounters& w = top_sim::work_counters();
  Counts c;
  c.seconds = scene.duration;
  top_sim::Simulator sim(scene);
  const std::uint64_t a0 = w.sample_analyses, s0 = w.stationary_solves, m0 = top_sim_counting::heap_allocations();
  sim.advance_to(scene.duration);
  c.allocations = top_sim_counting::heap_allocations() - m0;
  c.analyses = w.sample_analyses - a0;
  c.solves = w.stationary_solves - s0;
  c.stats = sim.stats();
  c.switches = sim.mode_switch_count();
  if (sim.fault() != top_sim::ContactFault::none) c.fault = sim.fault_message();
  const std::uint64_t a1 = w.sample_analyses;
  (void)sim.snapshot();
  c.first_read = w.sample_analyses - a1;
  (void)sim.snapshot();
  c.second_read = w.sample_analyses - a1 - c.first_read;
  return c;
}

void print_row(const std::string& name, const Counts& c) {
  const std::uint64_t tried = c.stats.steps + c.stats.rejected;
  std::printf("| %s | %g | %llu | %llu | %llu | %.3f | %llu | %llu | %.3g | %llu | %.3g | %llu / %llu |%s\n",
              name.c_str(), c.seconds, static_cast<unsigned long long>(c.stats.steps),
              static_cast<unsigned long long>(c.stats.rejected),
              static_cast<unsigned long long>(c.stats.rhs_evaluations),
              tried ? static_cast<double>(c.stats.rhs_evaluations) / static_cast<double>(tried) : 0.0,
              static_cast<unsigned long long>(c.switches), static_cast<unsigned long long>(c.analyses),
              static_cast<double>(c.solves) / c.seconds, static_cast<unsigned long long>(c.allocations),
              c.stats.steps ? static_cast<double>(c.allocations) / static_cast<double>(c.stats.steps) : 0.0,
              static_cast<unsigned long long>(c.first_read), static_cast<unsigned long long>(c.second_read),
              c.fault.empty() ? "" : (" fault: " + c.fault).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string config = argc > 1 ? argv[1] : top_sim::default_config_dir();
  std::printf("| scene | simulated [s] | steps | rejected | right-hand sides | per step tried | mode switches | "
              "sample analyses, unread | stationary solves per simulated s, unread | heap allocations | per step | "
              "analyses at 1st / 2nd read |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int faults = 0;
  for (const char* name : {"default", "frictionless", "coulomb", "hopping", "tippe_top"}) {
    try {
      const Counts c = count_run(config + "/scenes/" + name + ".yaml");
      print_row(std::string(name) + ".yaml", c);
      faults += c.fault.empty() ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "work_counts: %s.yaml: %s\n", name, e.what());
      return 1;
    }
  }
  return faults == 0 ? 0 : 1;
}
